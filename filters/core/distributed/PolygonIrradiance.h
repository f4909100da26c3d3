#pragma once
// A planar polygon emitting uniformly (a Lambertian emitter of radiance L): its exact
// irradiance E = L P at a point, through the projected solid angle P (docs/formulas.md
// sections 11.1 and 11.2).
#include "Vec3.h"

#include <vector>

namespace shadelab
{
/// P = E / L = integral over the polygon's directions above the receiver's tangent plane of
/// max(0, n.w) dw, by Lambert's formula after clipping the polygon to that half-space. The
/// vertices are those of a planar polygon, convex or not, in either winding (the value is the
/// same: the caller decides which side emits). 0 for a degenerate polygon and for a point in
/// the polygon's plane (within 1e-12 of the polygon's size), which sees it edge-on.
double polygonProjectedSolidAngle(
  const std::vector<glm::dvec3>& vertices, const glm::dvec3& point, const glm::dvec3& unitNormal);

/// The unit normal by Newell's method, oriented by the winding (counter-clockwise seen from
/// where it points); the zero vector for a polygon with no area.
glm::dvec3 polygonNormal(const std::vector<glm::dvec3>& vertices);

/// The area of a planar polygon, convex or not, from Newell's vector.
double polygonArea(const std::vector<glm::dvec3>& vertices);
}
