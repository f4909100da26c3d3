#pragma once
// Vector types shared by the core. GLM is header-only, and its vec<3, T> lets every
// formula be written once for float32 and float64 arithmetic.
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>

namespace shadelab
{
template<typename T>
using Vec3 = glm::vec<3, T, glm::defaultp>;

/// Linear RGB triple (light colours, material coefficients).
using Rgb = glm::dvec3;

template<typename T>
bool isFinite(const Vec3<T>& v)
{
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

/// The largest absolute component: 0 only for the zero vector, and never overflows.
inline double largestComponent(const glm::dvec3& v)
{
  return std::max({ std::abs(v.x), std::abs(v.y), std::abs(v.z) });
}

/// |v| for any finite v, without the overflow of squaring components above 1e154.
inline double vectorLength(const glm::dvec3& v)
{
  const double scale = largestComponent(v);
  return scale > 0 ? scale * glm::length(v / scale) : 0.0;
}

/// v / |v| for any finite non-zero v. glm::normalize squares the components first, so it
/// returns 0 for |v| above 1e154 and for |v| below 1e-154; scaling by the largest component
/// first keeps the squares near 1.
inline glm::dvec3 unitVector(const glm::dvec3& v)
{
  return glm::normalize(v / largestComponent(v));
}

/// Two unit vectors completing unit n to a right-handed orthonormal basis, t x b = n (T. Duff
/// et al., "Building an Orthonormal Basis, Revisited", JCGT 6(1), 2017): no branch on n's
/// largest component and no loss of precision near any axis.
inline void orthonormalBasis(const glm::dvec3& n, glm::dvec3& t, glm::dvec3& b)
{
  const double sign = std::copysign(1.0, n.z);
  const double a = -1.0 / (sign + n.z);
  const double c = n.x * n.y * a;
  t = { 1.0 + sign * n.x * n.x * a, sign * c, -sign * n.x };
  b = { c, sign + n.y * n.y * a, -n.y };
}
}
