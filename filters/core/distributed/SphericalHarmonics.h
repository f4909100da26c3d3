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
#include "IrradiancePolynomial.h"

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

IrradiancePolynomial irradiancePolynomial(const ShCoefficients9& coefficients);

/// The polynomial n -> p(a n): the same irradiance in a frame turned by a (for a map turned
/// in the world, a takes world directions into the map's frame).
IrradiancePolynomial composedWith(const IrradiancePolynomial& p, const glm::dmat3& a);

/// R&H eq. 13: the irradiance E(n) = integral of L(w) max(0, n.w) dw of the radiance the
/// coefficients represent.
Rgb irradianceFromSh9(const ShCoefficients9& coefficients, const glm::dvec3& unitNormal);

/// The largest error of the nine coefficients' irradiance at any normal (docs/formulas.md
/// section 12.5): 3/32 of the map's total radiance times solid angle, per channel.
Rgb sh9IrradianceErrorBound(const EnvironmentMap& map);
}
