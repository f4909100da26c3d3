#pragma once
// A sphere emitting uniformly (a Lambertian emitter of radiance L): its exact irradiance
// E = L P at a point, through the projected solid angle P (docs/formulas.md sections 11.1
// and 11.3).
#include "Vec3.h"

namespace shadelab
{
/// P = E / L = integral over the directions that meet the sphere, above the receiver's tangent
/// plane, of max(0, n.w) dw: pi cos(beta) (r/d)^2 while the sphere is wholly above the horizon,
/// 0 once it is wholly below, Snyder's formula in between. A point on or inside the sphere sees
/// it in every direction of its upper hemisphere: pi.
double sphereProjectedSolidAngle(
  const glm::dvec3& centre, double radius, const glm::dvec3& point, const glm::dvec3& unitNormal);
}
