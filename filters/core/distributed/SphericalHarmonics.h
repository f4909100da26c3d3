#pragma once
// The irradiance environment map of Ramamoorthi and Hanrahan, "An Efficient Representation
// for Irradiance Environment Maps", SIGGRAPH 2001 (docs/formulas.md section 12.4): the radiance
// projected on the 9 real spherical harmonics of bands 0 to 2, from which the irradiance at
// any normal is a quadratic polynomial of the normal (their eq. 13). About 1% error on
// average; the worst case is a small bright source, at most about 9% of its peak.
//
// Axes: R&H write the basis and eq. 13 in x, y, z with z as their polar axis. We use the
// world x, y, z of EnvironmentMap.h as they stand (our up axis y is not their z). This is
// valid because the irradiance depends only on dot products of directions: any orthonormal
// frame works if the projection and eq. 13 use the same one, as both do here.
#include "EnvironmentMap.h"

#include <glm/mat3x3.hpp>

#include <array>

namespace shadelab
{
/// Coefficients L_lm in the order (l, m) = (0, 0), (1, -1), (1, 0), (1, 1), (2, -2), (2, -1),
/// (2, 0), (2, 1), (2, 2).
using ShCoefficients9 = std::array<Rgb, 9>;

/// The 9 basis functions Y_lm at a unit direction, in the order of ShCoefficients9.
std::array<double, 9> shBasis9(const glm::dvec3& unitDirection);

/// L_lm = sum over texels of L Y_lm(texel centre direction) texel solid angle.
ShCoefficients9 projectRadiance(const EnvironmentMap& map);

/// R&H eq. 13 as the coefficients of a quadratic polynomial in the normal's components, so
/// that a vectorised loop can evaluate it (ShadingKernel):
/// E(n) = xx x^2 + yy y^2 + zz z^2 + xy x y + xz x z + yz y z + x x + y y + z z + constant.
struct IrradiancePolynomial
{
  Rgb xx{ 0.0 }, yy{ 0.0 }, zz{ 0.0 }, xy{ 0.0 }, xz{ 0.0 }, yz{ 0.0 }, x{ 0.0 }, y{ 0.0 }, z{ 0.0 }, constant{ 0.0 };

  Rgb operator()(const glm::dvec3& n) const
  {
    return xx * (n.x * n.x) + yy * (n.y * n.y) + zz * (n.z * n.z) + xy * (n.x * n.y) + xz * (n.x * n.z) +
      yz * (n.y * n.z) + x * n.x + y * n.y + z * n.z + constant;
  }
};

IrradiancePolynomial irradiancePolynomial(const ShCoefficients9& coefficients);

/// The polynomial n -> p(a n): the same irradiance in a frame turned by a (for a map turned
/// in the world, a takes world directions into the map's frame).
IrradiancePolynomial composedWith(const IrradiancePolynomial& p, const glm::dmat3& a);

/// R&H eq. 13: the irradiance E(n) = integral of L(w) max(0, n.w) dw of the radiance the
/// coefficients represent.
Rgb irradianceFromSh9(const ShCoefficients9& coefficients, const glm::dvec3& unitNormal);
}
