#pragma once
// Where a ray from a surface point starts, so that it does not hit the surface it leaves.
//
// A fixed distance fails at some scale: too small far from the origin, where float32 rounds a
// point by more than it, too large on a small mesh, where it jumps over real occluders
// (docs/formulas.md section 20). Following C. Wachter and N. Binder, "A Fast and Robust Method for
// Avoiding Self-Intersection", Ray Tracing Gems (2019), chapter 6, the origin moves along the
// normal by a fixed number of float32 units in the last place of each coordinate (so by a
// distance in proportion to the coordinate's own rounding error), and by a small absolute
// amount near 0, where units in the last place become too fine. ShadeLab casts rays in a frame
// where the mesh's bounding sphere is the unit sphere, so "near 0" and "a few ULPs" mean the
// same thing on every mesh, whatever its size or position.
#include <glm/vec3.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>

namespace shadelab
{
/// The ULPs a coordinate moves per unit of the normal's component, and the absolute move per
/// unit where the coordinate is below originThreshold (the constants of Wachter and Binder).
constexpr float offsetUlpsPerUnit = 256.0f;
constexpr float offsetNearZero = 1.0f / 65536.0f;
constexpr float originThreshold = 1.0f / 32.0f;

/// x moved by `ulps` units in its last place: up for ulps > 0, down for ulps < 0, by integer
/// arithmetic on the float's bits as Wachter and Binder do.
inline float movedByUlps(float x, std::int32_t ulps)
{
  std::int32_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  bits += x < 0 ? -ulps : ulps;
  float moved;
  std::memcpy(&moved, &bits, sizeof moved);
  return moved;
}

/// The origin of a ray leaving the surface at p (in the ray frame) on the side of the unit
/// vector n.
inline glm::vec3 offsetRayOrigin(const glm::vec3& p, const glm::vec3& n)
{
  glm::vec3 origin;
  for (int i = 0; i < 3; ++i)
  {
    origin[i] = std::abs(p[i]) < originThreshold
      ? p[i] + offsetNearZero * n[i]
      : movedByUlps(p[i], static_cast<std::int32_t>(offsetUlpsPerUnit * n[i]));
  }
  return origin;
}
}
