#pragma once
// A disk emitting uniformly (a Lambertian emitter of radiance L): its exact irradiance
// E = L P at a point, through the projected solid angle P (docs/formulas.md sections 11.1
// and 11.4).
#include "Vec3.h"

namespace shadelab
{
/// P = E / L = integral over the disk's directions above the receiver's tangent plane of
/// max(0, n.w) dw, from Lambert's formula on the disk's rim (adaptive Gauss-Legendre
/// quadrature) and, where the tangent plane cuts the disk, on the chord it cuts. Accurate to
/// about 1e-13 relative and 1e-15 absolute (P is at most pi). Within a distance delta of the
/// rim the absolute error grows to about 1e-15 r / delta; P changes by O(1) over a distance
/// delta there, so that rounding p itself moves it about as much.
/// The value is the same from either side of the disk: the caller decides which side emits. A
/// point closer to the disk's plane than 1e-12 r sees the disk edge-on and gets 0.
double diskProjectedSolidAngle(const glm::dvec3& centre, const glm::dvec3& unitDiskNormal, double radius,
  const glm::dvec3& point, const glm::dvec3& unitNormal);
}
