#include "SphericalHarmonics.h"

#include <glm/gtc/constants.hpp>

#include <cmath>
#include <vector>

namespace shadelab
{
namespace
{
constexpr double pi = glm::pi<double>();

// R&H eq. 10 gives the basis constants to 6 digits (0.282095, 0.488603, 1.092548, 0.315392,
// 0.546274). These are their closed forms: with the rounded ones a constant map's irradiance
// would be 8e-7 off pi L (0.886227 x 0.282095 x 4 = 1 + 8e-7). Square roots as literals, so
// that the constants are constexpr.
constexpr double sqrtPi = 1.77245385090551602730;
constexpr double sqrt3 = 1.73205080756887729353;
constexpr double sqrt5 = 2.23606797749978969641;
constexpr double sqrt15 = 3.87298334620741688518;
constexpr double y00 = 0.5 / sqrtPi; // 1 / sqrt(4 pi)
constexpr double y1 = 0.5 * sqrt3 / sqrtPi; // sqrt(3 / (4 pi))
constexpr double y2Product = 0.5 * sqrt15 / sqrtPi; // Y2-2, Y2-1, Y21: sqrt(15 / (4 pi))
constexpr double y20 = 0.25 * sqrt5 / sqrtPi; // sqrt(5 / (16 pi))
constexpr double y22 = 0.25 * sqrt15 / sqrtPi; // sqrt(15 / (16 pi))

// Eq. 13's c1..c5 (0.429043, 0.511664, 0.743125, 0.886227, 0.247708) are the clamped
// cosine's band factors A0 = pi, A1 = 2 pi / 3, A2 = pi / 4 (eq. 8 and 9) times the basis
// constants: E(n) = sum of A_l L_lm Y_lm(n) (eq. 12). R&H multiplied the rounded constants,
// so their c2 and c3 differ from these in the sixth digit.
constexpr double c1 = 0.25 * pi * y22;
constexpr double c2 = pi / 3.0 * y1;
constexpr double c3 = 0.75 * pi * y20;
constexpr double c4 = pi * y00;
constexpr double c5 = 0.25 * pi * y20;
}

// R&H eq. 10.
std::array<double, 9> shBasis9(const glm::dvec3& unitDirection)
{
  const double x = unitDirection.x;
  const double y = unitDirection.y;
  const double z = unitDirection.z;
  return { y00, y1 * y, y1 * z, y1 * x, y2Product * x * y, y2Product * y * z,
    y20 * (3.0 * z * z - 1.0), y2Product * x * z, y22 * (x * x - y * y) };
}

ShCoefficients9 projectRadiance(const EnvironmentMap& map)
{
  requireValidShape(map, "projectRadiance");
  // Texel centre directions from per-column and per-row sines and cosines (EnvironmentMap.h):
  // no trigonometry per texel.
  std::vector<double> sinPhi(map.width);
  std::vector<double> cosPhi(map.width);
  for (int column = 0; column < map.width; ++column)
  {
    const double phi = 2.0 * pi * ((column + 0.5) / map.width - 0.5);
    sinPhi[column] = std::sin(phi);
    cosPhi[column] = std::cos(phi);
  }

  ShCoefficients9 coefficients;
  coefficients.fill(Rgb(0.0));
  for (int row = 0; row < map.height; ++row)
  {
    const double theta = pi * (row + 0.5) / map.height;
    const double sinTheta = std::sin(theta);
    const double cosTheta = std::cos(theta);
    // Every texel of a row has the same solid angle: sum the row, then weight it once.
    ShCoefficients9 rowSums;
    rowSums.fill(Rgb(0.0));
    for (int column = 0; column < map.width; ++column)
    {
      const glm::dvec3 direction(
        sinTheta * sinPhi[column], cosTheta, -sinTheta * cosPhi[column]);
      const std::array<double, 9> basis = shBasis9(direction);
      const Rgb& radiance = map.texel(column, row);
      for (int k = 0; k < 9; ++k)
      {
        rowSums[k] += radiance * basis[k];
      }
    }
    const double solidAngle = texelSolidAngle(row, map.width, map.height);
    for (int k = 0; k < 9; ++k)
    {
      coefficients[k] += rowSums[k] * solidAngle;
    }
  }
  return coefficients;
}

// R&H eq. 13: E = c1 L22 (x^2 - y^2) + c3 L20 z^2 + c4 L00 - c5 L20
//   + 2 c1 (L2-2 xy + L21 xz + L2-1 yz) + 2 c2 (L11 x + L1-1 y + L10 z).
IrradiancePolynomial irradiancePolynomial(const ShCoefficients9& coefficients)
{
  const auto& [l00, l1m1, l10, l11, l2m2, l2m1, l20, l21, l22] = coefficients;
  IrradiancePolynomial e;
  e.xx = c1 * l22;
  e.yy = -c1 * l22;
  e.zz = c3 * l20;
  e.xy = 2.0 * c1 * l2m2;
  e.xz = 2.0 * c1 * l21;
  e.yz = 2.0 * c1 * l2m1;
  e.x = 2.0 * c2 * l11;
  e.y = 2.0 * c2 * l1m1;
  e.z = 2.0 * c2 * l10;
  e.constant = c4 * l00 - c5 * l20;
  return e;
}

IrradiancePolynomial composedWith(const IrradiancePolynomial& p, const glm::dmat3& a)
{
  // Per channel, p(m) = m^T S m + b.m + c with S symmetric; p(a n) = n^T (a^T S a) n + (a^T b).n + c.
  IrradiancePolynomial q;
  q.constant = p.constant;
  for (int channel = 0; channel < 3; ++channel)
  {
    const double xy = p.xy[channel] / 2, xz = p.xz[channel] / 2, yz = p.yz[channel] / 2;
    const glm::dmat3 square(glm::dvec3(p.xx[channel], xy, xz), glm::dvec3(xy, p.yy[channel], yz),
      glm::dvec3(xz, yz, p.zz[channel]));
    const glm::dmat3 turned = glm::transpose(a) * square * a;
    const glm::dvec3 linear = glm::transpose(a) * glm::dvec3(p.x[channel], p.y[channel], p.z[channel]);
    q.xx[channel] = turned[0][0];
    q.yy[channel] = turned[1][1];
    q.zz[channel] = turned[2][2];
    q.xy[channel] = 2 * turned[0][1];
    q.xz[channel] = 2 * turned[0][2];
    q.yz[channel] = 2 * turned[1][2];
    q.x[channel] = linear.x;
    q.y[channel] = linear.y;
    q.z[channel] = linear.z;
  }
  return q;
}

Rgb irradianceFromSh9(const ShCoefficients9& coefficients, const glm::dvec3& unitNormal)
{
  return irradiancePolynomial(coefficients)(unitNormal);
}

Rgb sh9IrradianceErrorBound(const EnvironmentMap& map)
{
  Rgb total(0.0);
  for (int row = 0; row < map.height; ++row)
  {
    const double solidAngle = texelSolidAngle(row, map.width, map.height);
    for (int column = 0; column < map.width; ++column)
    {
      total += map.texel(column, row) * solidAngle;
    }
  }
  return 3.0 / 32.0 * total;
}
}
