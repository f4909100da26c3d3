#include "SphericalHarmonics.h"

#include "GaussLegendre.h"

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace shadelab
{
namespace
{
constexpr double pi = glm::pi<double>();

// R&H eq. 10's basis constants, which eq. 13's c1..c5 below are built from. R&H give them to 6
// digits (0.282095, 0.488603, 1.092548, 0.315392, 0.546274); these are their closed forms: with
// the rounded ones a constant map's irradiance would be 8e-7 off pi L (0.886227 x 0.282095 x 4
// = 1 + 8e-7). Square roots as literals, so that the constants are constexpr.
constexpr double sqrtPi = 1.77245385090551602730;
constexpr double sqrt3 = 1.73205080756887729353;
constexpr double sqrt5 = 2.23606797749978969641;
constexpr double sqrt15 = 3.87298334620741688518;
constexpr double y00 = 0.5 / sqrtPi;           // 1 / sqrt(4 pi)
constexpr double y1 = 0.5 * sqrt3 / sqrtPi;    // sqrt(3 / (4 pi))
constexpr double y20 = 0.25 * sqrt5 / sqrtPi;  // sqrt(5 / (16 pi))
constexpr double y22 = 0.25 * sqrt15 / sqrtPi; // sqrt(15 / (16 pi))

// Eq. 13's c1..c5 (0.429043, 0.511664, 0.743125, 0.886227, 0.247708) are the clamped
// cosine's band factors A0 = pi, A1 = 2 pi / 3, A2 = pi / 4 (eq. 8 and 9) times the basis
// constants: E(n) = sum of A_l L_lm Y_lm(n) (eq. 12). R&H multiplied the rounded constants,
// so their c2 and c3 differ from these in the sixth digit.
constexpr double c1 = clampedCosineBand(2) * y22;
constexpr double c2 = clampedCosineBand(1) / 2 * y1;
constexpr double c3 = 3 * clampedCosineBand(2) * y20;
constexpr double c4 = clampedCosineBand(0) * y00;
constexpr double c5 = clampedCosineBand(2) * y20;
}

namespace
{
/// K_lm = sqrt((2l + 1) (l - m)! / (4 pi (l + m)!)) at shIndex(l, m) for m >= 0, times sqrt(2)
/// for m > 0: computed once.
const ShBasis& normalisations()
{
  static const ShBasis table = []
  {
    ShBasis k{};
    for (int l = 0; l <= largestShOrder; ++l)
    {
      for (int m = 0; m <= l; ++m)
      {
        double factorialRatio = 1; // (l - m)! / (l + m)!
        for (int f = l - m + 1; f <= l + m; ++f)
        {
          factorialRatio /= f;
        }
        k[shIndex(l, m)] = std::sqrt((2 * l + 1) * factorialRatio / (4 * pi)) * (m > 0 ? std::sqrt(2.0) : 1.0);
      }
    }
    return k;
  }();
  return table;
}
}

void requireShOrder(int order, const char* who)
{
  if (order < 0 || order > largestShOrder)
  {
    throw std::invalid_argument(
      std::string(who) + ": order " + std::to_string(order) + " is not in 0 to " + std::to_string(largestShOrder));
  }
}

namespace
{
// The associated Legendre functions by their recurrences in z (Press et al., "Numerical
// Recipes", 3rd ed., 2007, section 6.7), as Q_l^m = P_l^m / sin^m(theta), whose sin^m(theta)
// goes with the azimuth: sin^m(theta) (cos(m phi), sin(m phi)) = (Re, Im) of (x + i y)^m,
// taken by one complex product per m. No trigonometry, and no division by sin(theta) at the
// poles (P.-P. Sloan, "Efficient Spherical Harmonic Evaluation", JCGT 2(2), 2013, does the same
// in generated code).
/// shBasis's first shCount(Order) values, at a fixed order and inlined so that the compiler
/// unrolls the loops and keeps the values in registers: the projection of a map evaluates it at
/// every texel.
template<int Order>
[[gnu::always_inline]] inline std::array<double, shCount(Order)> basisOfOrder(
  const glm::dvec3& unitDirection, const ShBasis& normalisation)
{
  std::array<double, shCount(Order)> basis;
  const double x = unitDirection.x, y = unitDirection.y, z = unitDirection.z;
  double real = 1, imaginary = 0; // (x + i y)^m
  double qmm = 1;                 // Q_m^m = (2m - 1)!!
  for (int m = 0; m <= Order; ++m)
  {
    double qBefore = 0, q = qmm; // Q_{l-1}^m and Q_l^m, from l = m
    for (int l = m; l <= Order; ++l)
    {
      if (l == m + 1)
      {
        qBefore = q;
        q = (2 * m + 1) * z * qmm;
      }
      else if (l > m + 1)
      {
        const double next = ((2 * l - 1) * z * q - (l + m - 1) * qBefore) / (l - m);
        qBefore = q;
        q = next;
      }
      const double k = normalisation[shIndex(l, m)];
      if (m == 0)
      {
        basis[shIndex(l, 0)] = k * q;
      }
      else
      {
        basis[shIndex(l, m)] = k * q * real;
        basis[shIndex(l, -m)] = k * q * imaginary;
      }
    }
    const double nextReal = real * x - imaginary * y;
    imaginary = real * y + imaginary * x;
    real = nextReal;
    qmm *= 2 * m + 1;
  }
  return basis;
}

/// Calls f with the order as a compile-time constant (std::integral_constant).
template<typename F>
decltype(auto) withOrder(int order, F&& f)
{
  assert(order >= 0 && order <= largestShOrder);
  switch (order)
  {
    case 0: return f(std::integral_constant<int, 0>());
    case 1: return f(std::integral_constant<int, 1>());
    case 2: return f(std::integral_constant<int, 2>());
    case 3: return f(std::integral_constant<int, 3>());
    default: return f(std::integral_constant<int, largestShOrder>());
  }
}

/// projectRadiance at a fixed order: the sums in fixed-size arrays.
template<int Order>
ShCoefficients projectedToOrder(const EnvironmentMap& map)
{
  constexpr int count = shCount(Order);
  const ShBasis& normalisation = normalisations();
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
  std::array<Rgb, count> coefficients;
  coefficients.fill(Rgb(0.0));
  for (int row = 0; row < map.height; ++row)
  {
    const double theta = pi * (row + 0.5) / map.height;
    const double sinTheta = std::sin(theta);
    const double cosTheta = std::cos(theta);
    // Every texel of a row has the same solid angle: sum the row, then weight it once.
    std::array<Rgb, count> rowSums;
    rowSums.fill(Rgb(0.0));
    for (int column = 0; column < map.width; ++column)
    {
      const glm::dvec3 direction(sinTheta * sinPhi[column], cosTheta, -sinTheta * cosPhi[column]);
      const std::array<double, count> basis = basisOfOrder<Order>(direction, normalisation);
      const Rgb& radiance = map.texel(column, row);
      for (int k = 0; k < count; ++k)
      {
        rowSums[k] += radiance * basis[k];
      }
    }
    const double solidAngle = texelSolidAngle(row, map.width, map.height);
    for (int k = 0; k < count; ++k)
    {
      coefficients[k] += rowSums[k] * solidAngle;
    }
  }
  return ShCoefficients(coefficients.begin(), coefficients.end());
}
}

ShBasis shBasis(int order, const glm::dvec3& unitDirection)
{
  ShBasis basis{};
  withOrder(order,
    [&](auto fixed)
    {
      const auto values = basisOfOrder<decltype(fixed)::value>(unitDirection, normalisations());
      std::copy(values.begin(), values.end(), basis.begin());
    });
  return basis;
}

std::vector<SphereNode> sphereQuadrature(int degree)
{
  const GaussLegendreRule rule = gaussLegendreRule(degree / 2 + 1);
  const int azimuths = degree + 1;
  std::vector<SphereNode> nodes;
  for (std::size_t i = 0; i < rule.nodes.size(); ++i)
  {
    const double z = rule.nodes[i], weight = rule.weights[i];
    const double sinTheta = std::sqrt(1 - z * z);
    for (int j = 0; j < azimuths; ++j)
    {
      const double phi = 2 * pi * j / azimuths;
      nodes.push_back({ { sinTheta * std::cos(phi), sinTheta * std::sin(phi), z }, weight * 2 * pi / azimuths });
    }
  }
  return nodes;
}

std::array<double, 9> shBasis9(const glm::dvec3& unitDirection)
{
  const ShBasis basis = shBasis(2, unitDirection);
  std::array<double, 9> first;
  std::copy_n(basis.begin(), 9, first.begin());
  return first;
}

ShCoefficients9 projectRadiance(const EnvironmentMap& map)
{
  const ShCoefficients coefficients = projectRadiance(map, 2);
  ShCoefficients9 first;
  std::copy_n(coefficients.begin(), 9, first.begin());
  return first;
}

ShCoefficients projectRadiance(const EnvironmentMap& map, int order)
{
  requireShOrder(order, "projectRadiance");
  requireValidShape(map, "projectRadiance");
  return withOrder(order, [&](auto fixed) { return projectedToOrder<decltype(fixed)::value>(map); });
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
    const glm::dmat3 square(
      glm::dvec3(p.xx[channel], xy, xz), glm::dvec3(xy, p.yy[channel], yz), glm::dvec3(xz, yz, p.zz[channel]));
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

double clampedCosineTruncationPeak(int order)
{
  if (order < 2 || order > largestShOrder)
  {
    throw std::invalid_argument(
      "clampedCosineTruncationPeak: order " + std::to_string(order) + " is not 2 to " + std::to_string(largestShOrder));
  }
  // The series at t = 0: sum of A_l (2l + 1) / (4 pi) P_l(0), P_l(0) = 0 for odd l and
  // (-1)^(l/2) (l - 1)!! / l!! for even l. Orders 2 to 4 err most there (a test scans [-1, 1]).
  double atHorizon = 0;
  double legendreAtZero = 1;
  for (int l = 0; l <= order; l += 2)
  {
    if (l > 0)
    {
      legendreAtZero *= -double(l - 1) / double(l);
    }
    atHorizon += clampedCosineBand(l) * (2 * l + 1) / (4 * pi) * legendreAtZero;
  }
  return std::abs(atHorizon);
}

Rgb shIrradianceErrorBound(const EnvironmentMap& map, int order)
{
  const double peak = clampedCosineTruncationPeak(order);
  Rgb total(0.0);
  for (int row = 0; row < map.height; ++row)
  {
    const double solidAngle = texelSolidAngle(row, map.width, map.height);
    for (int column = 0; column < map.width; ++column)
    {
      total += map.texel(column, row) * solidAngle;
    }
  }
  return peak * total;
}
}
