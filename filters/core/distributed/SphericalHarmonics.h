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
#include "ShBands.h"

#include <glm/mat3x3.hpp>

#include <array>
#include <vector>

namespace shadelab
{
/// Throws std::invalid_argument, naming `who`, unless 0 <= order <= largestShOrder.
void requireShOrder(int order, const char* who);

/// The real spherical harmonics of bands 0 to order (0 to largestShOrder) at a unit direction,
/// at shIndex(l, m), the entries past shCount(order) 0: sqrt(2) K_lm P_l^m(z) cos(m phi) for
/// m > 0, sqrt(2) K_l|m| P_l^|m|(z) sin(|m| phi) for m < 0, K_l0 P_l(z) for m = 0, with
/// K_lm = sqrt((2l + 1) (l - m)! / (4 pi (l + m)!)), x = sin(theta) cos(phi), y = sin(theta)
/// sin(phi), z = cos(theta), and no Condon-Shortley phase (the graphics convention: Y_11 is
/// +sqrt(3 / (4 pi)) x). Bands 0 to 2 are R&H's eq. 10.
ShBasis shBasis(int order, const glm::dvec3& unitDirection);

/// A direction on the unit sphere and its weight in a quadrature rule.
struct SphereNode
{
  glm::dvec3 direction;
  double weight;
};

/// A rule that integrates every polynomial of x, y, z up to `degree` over the unit sphere
/// exactly (to rounding): Gauss-Legendre nodes in z = cos(theta), degree / 2 + 1 of them, times
/// degree + 1 equally spaced azimuths (exact for cos(k phi) and sin(k phi) up to k = degree).
/// A product of two spherical harmonics of band l is such a polynomial of degree 2l.
std::vector<SphereNode> sphereQuadrature(int degree);

/// Coefficients L_lm in the order (l, m) = (0, 0), (1, -1), (1, 0), (1, 1), (2, -2), (2, -1),
/// (2, 0), (2, 1), (2, 2).
using ShCoefficients9 = std::array<Rgb, 9>;
/// Coefficients of bands 0 to some order, at shIndex(l, m): shCount(order) of them.
using ShCoefficients = std::vector<Rgb>;

/// The 9 basis functions Y_lm at a unit direction, in the order of ShCoefficients9.
std::array<double, 9> shBasis9(const glm::dvec3& unitDirection);

/// L_lm = sum over texels of L Y_lm(texel centre direction) texel solid angle, for bands 0
/// to order (at most largestShOrder).
ShCoefficients projectRadiance(const EnvironmentMap& map, int order);
/// Bands 0 to 2.
ShCoefficients9 projectRadiance(const EnvironmentMap& map);

/// A_l, the clamped cosine max(0, cos theta)'s band factor (R&H eq. 8 and 9): the integral of
/// L(w) max(0, n.w) is the sum over l, m of A_l L_lm Y_lm(n) (the Funk-Hecke theorem). pi,
/// 2 pi / 3, pi / 4, 0, -pi / 24 for l = 0 to 4; 0 for every odd l above 1 (and below 0).
constexpr double clampedCosineBand(int l)
{
  constexpr double pi = 3.14159265358979323846;
  if (l < 0)
  {
    return 0;
  }
  if (l == 1)
  {
    return 2 * pi / 3;
  }
  if (l % 2 == 1)
  {
    return 0;
  }
  // 2 pi (-1)^(l/2 - 1) / ((l + 2) (l - 1)) times l! / (2^l ((l/2)!)^2), the central binomial
  // coefficient over 2^l, built up as a product.
  double central = 1;
  for (int k = 1; k <= l / 2; ++k)
  {
    central *= double(l / 2 + k) / (4.0 * k);
  }
  const double sign = (l / 2) % 2 == 1 ? 1.0 : -1.0;
  return 2 * pi * sign / ((l + 2) * (l - 1)) * central;
}

IrradiancePolynomial irradiancePolynomial(const ShCoefficients9& coefficients);

/// The polynomial n -> p(a n): the same irradiance in a frame turned by a (for a map turned
/// in the world, a takes world directions into the map's frame).
IrradiancePolynomial composedWith(const IrradiancePolynomial& p, const glm::dmat3& a);

/// R&H eq. 13: the irradiance E(n) = integral of L(w) max(0, n.w) dw of the radiance the
/// coefficients represent.
Rgb irradianceFromSh9(const ShCoefficients9& coefficients, const glm::dvec3& unitNormal);

/// The largest size of max(0, t) less its Legendre series cut after band `order` (2 to
/// largestShOrder; others throw std::invalid_argument): 3/32 for orders 2 and 3, 15/256 for 4,
/// each at the horizon t = 0 (docs/formulas.md sections 12.5 and 12.10).
double clampedCosineTruncationPeak(int order);

/// The largest error at any normal of the irradiance from the map's coefficients to band
/// `order` (2 to largestShOrder; docs/formulas.md section 12.5): clampedCosineTruncationPeak
/// times the map's total radiance times solid angle, per channel.
Rgb shIrradianceErrorBound(const EnvironmentMap& map, int order);
}
