#pragma once
// Vector types shared by the core. GLM is header-only, and its vec<3, T> lets every
// formula be written once for float32 and float64 arithmetic.
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace shadelab
{
template <typename T>
using Vec3 = glm::vec<3, T, glm::defaultp>;

/// Linear RGB triple (light colours, material coefficients).
using Rgb = glm::dvec3;
}
