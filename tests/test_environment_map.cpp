// Environment maps: orientation, texel solid angles, downsampling, the bundled map read from
// its two files (test_map_files.cpp reads the maps it writes), the 9-coefficient irradiance of
// Ramamoorthi and Hanrahan, and importance sampling by luminance.
#include "EnvironmentMap.h"
#include "EnvironmentSampler.h"
#include "ShRotation.h"
#include "SphericalHarmonics.h"
#include "TestPaths.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <iostream>
#include <limits>
#include <numeric>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace
{
using namespace shadelab;
constexpr double pi = M_PI;
const std::string venicePath = shadelab::testing::sourcePath("data/envmaps/venice_sunset_1k");

EnvironmentMap mapOf(int width, int height, const std::function<Rgb(const glm::dvec3&)>& radianceAt)
{
  EnvironmentMap map;
  map.width = width;
  map.height = height;
  for (int row = 0; row < height; ++row)
  {
    for (int column = 0; column < width; ++column)
    {
      map.radiance.push_back(radianceAt(texelCentreDirection(map, column, row)));
    }
  }
  return map;
}

/// The integral of radiance over the sphere: sum of radiance x texel solid angle.
Rgb radiantIntegral(const EnvironmentMap& map)
{
  Rgb sum(0.0);
  for (int row = 0; row < map.height; ++row)
  {
    for (int column = 0; column < map.width; ++column)
    {
      sum += map.texel(column, row) * texelSolidAngle(row, map.width, map.height);
    }
  }
  return sum;
}

/// The irradiance at n of the map's texels taken as point sources at their centres.
Rgb bruteForceIrradiance(const EnvironmentMap& map, const glm::dvec3& n)
{
  Rgb sum(0.0);
  for (int row = 0; row < map.height; ++row)
  {
    for (int column = 0; column < map.width; ++column)
    {
      const double cosine = std::max(0.0, glm::dot(n, texelCentreDirection(map, column, row)));
      sum += map.texel(column, row) * cosine * texelSolidAngle(row, map.width, map.height);
    }
  }
  return sum;
}

glm::dvec3 randomDirection(std::mt19937_64& random)
{
  std::normal_distribution<double> normal;
  return unitVector(glm::dvec3(normal(random), normal(random), normal(random)));
}

void expectNearVector(const glm::dvec3& actual, const glm::dvec3& expected, double tolerance)
{
  EXPECT_NEAR(actual.x, expected.x, tolerance);
  EXPECT_NEAR(actual.y, expected.y, tolerance);
  EXPECT_NEAR(actual.z, expected.z, tolerance);
}

double relativeError(const Rgb& actual, const Rgb& expected)
{
  return largestComponent(actual - expected) / largestComponent(expected);
}

// --- Geometry -------------------------------------------------------------------------------

TEST(EnvironmentMap, TexelSolidAnglesSumToFourPi)
{
  for (const auto& [width, height] : { std::pair(8, 4), std::pair(1024, 512) })
  {
    double sum = 0.0;
    for (int row = 0; row < height; ++row)
    {
      sum += width * texelSolidAngle(row, width, height);
    }
    EXPECT_NEAR(sum / (4.0 * pi), 1.0, 1e-12) << width << "x" << height;
  }
}

TEST(EnvironmentMap, TexelSolidAngleIsTheBandAreaOverTheWidth)
{
  // Row 0 of an 8x4 map: the cap theta <= pi/4 has area 2 pi (1 - cos(pi/4)).
  EXPECT_DOUBLE_EQ(texelSolidAngle(0, 8, 4), 2.0 * pi * (1.0 - std::sqrt(0.5)) / 8.0);
}

TEST(EnvironmentMap, Orientation)
{
  const double tolerance = 1e-15;
  expectNearVector(directionAt(0.5, 0.5), { 0, 0, -1 }, tolerance);
  expectNearVector(directionAt(0.75, 0.5), { 1, 0, 0 }, tolerance);
  expectNearVector(directionAt(0.25, 0.5), { -1, 0, 0 }, tolerance);
  expectNearVector(directionAt(0.0, 0.5), { 0, 0, 1 }, tolerance);
  expectNearVector(directionAt(1.0, 0.5), { 0, 0, 1 }, tolerance);
  for (const double u : { 0.0, 0.3, 0.5, 0.9 })
  {
    expectNearVector(directionAt(u, 0.0), { 0, 1, 0 }, tolerance);
    expectNearVector(directionAt(u, 1.0), { 0, -1, 0 }, tolerance);
  }
  // Texel (2, 0) of a 4x2 map is centred at u = 0.625, v = 0.25: theta = phi = pi/4.
  EnvironmentMap map;
  map.width = 4;
  map.height = 2;
  expectNearVector(texelCentreDirection(map, 2, 0), { 0.5, std::sqrt(0.5), -0.5 }, tolerance);
}

TEST(EnvironmentMap, UvOfDirectionInvertsDirectionAt)
{
  std::mt19937_64 random(1);
  std::uniform_real_distribution<double> uniform;
  for (int i = 0; i < 10000; ++i)
  {
    const glm::dvec3 direction = randomDirection(random);
    const glm::dvec2 uv = uvOfDirection(direction);
    EXPECT_GE(uv.x, 0.0);
    EXPECT_LT(uv.x, 1.0);
    expectNearVector(directionAt(uv.x, uv.y), direction, 1e-12);

    const glm::dvec2 drawn(uniform(random), uniform(random));
    const glm::dvec2 back = uvOfDirection(directionAt(drawn.x, drawn.y));
    EXPECT_NEAR(back.x, drawn.x, 1e-12);
    EXPECT_NEAR(back.y, drawn.y, 1e-12);
  }
  EXPECT_EQ(uvOfDirection({ 0, 0, 1 }).x, 0.0); // u = 1 wraps to 0
}

// texelToward finds most texels from a quick atan2 and the rest, within its error of a
// texel's edge, from the library's: the texel of uvOfDirection's (u, v) always, for random
// directions, for directions on the edges themselves and a rounding either side of them, at the
// poles and the seam, and for maps of every shape.
TEST(EnvironmentMap, TexelTowardIsTheTexelOfUvOfDirection)
{
  auto texelOfUv = [](const EnvironmentMap& map, const glm::dvec3& d)
  {
    const glm::dvec2 uv = uvOfDirection(d);
    return glm::ivec2(std::min(int(uv.x * map.width), map.width - 1), std::min(int(uv.y * map.height), map.height - 1));
  };
  std::mt19937_64 random(44);
  std::uniform_real_distribution<double> uniform;
  int compared = 0;
  for (const auto& [width, height] : { std::pair{ 1024, 512 }, std::pair{ 7, 3 }, std::pair{ 1, 1 } })
  {
    EnvironmentMap map;
    map.width = width;
    map.height = height;
    std::vector<glm::dvec3> directions = { { 0, 1, 0 }, { 0, -1, 0 }, { 0, 0, 1 }, { 0, 0, -1 }, { 1e-300, 1, 0 } };
    for (int i = 0; i < 200000; ++i)
    {
      directions.push_back(randomDirection(random));
    }
    for (int column = 0; column <= width; ++column)
    {
      for (int row = 0; row <= height; row += std::max(1, height / 8))
      {
        const glm::dvec3 edge = directionAt(double(column) / width, (row + uniform(random)) / height);
        directions.push_back(edge);
        for (const double nudge : { -1e-15, 1e-15 })
        {
          directions.push_back(glm::normalize(edge + nudge * glm::dvec3(edge.z, 0, -edge.x)));
        }
      }
    }
    for (const glm::dvec3& d : directions)
    {
      ASSERT_EQ(texelToward(map, d), texelOfUv(map, d))
        << width << "x" << height << " at " << d.x << " " << d.y << " " << d.z;
      ++compared;
    }
  }
  EXPECT_GT(compared, 600000);
}

TEST(EnvironmentMap, LuminanceOfPrimariesAndWhite)
{
  EXPECT_DOUBLE_EQ(luminance({ 1, 0, 0 }), 0.2126);
  EXPECT_DOUBLE_EQ(luminance({ 0, 1, 0 }), 0.7152);
  EXPECT_DOUBLE_EQ(luminance({ 0, 0, 1 }), 0.0722);
  EXPECT_DOUBLE_EQ(luminance({ 2, 2, 2 }), 2.0);
}

// --- Downsampling ---------------------------------------------------------------------------

TEST(Downsampled, KeepsTheIntegralOfRadiance)
{
  std::mt19937_64 random(2);
  std::uniform_real_distribution<double> uniform(0.0, 100.0);
  EnvironmentMap map;
  map.width = 64;
  map.height = 32;
  for (int i = 0; i < map.width * map.height; ++i)
  {
    map.radiance.emplace_back(uniform(random), uniform(random), uniform(random));
  }
  const Rgb integral = radiantIntegral(map);
  for (const int width : { 64, 32, 16, 8, 2 })
  {
    const EnvironmentMap coarse = downsampled(map, width);
    EXPECT_EQ(coarse.width, width);
    EXPECT_EQ(coarse.height, width / 2);
    EXPECT_LT(relativeError(radiantIntegral(coarse), integral), 1e-12) << width;
  }
}

TEST(Downsampled, ConstantMapStaysConstant)
{
  const Rgb value(0.25, 3.0, 1e4);
  const EnvironmentMap coarse = downsampled(mapOf(128, 64, [&](const glm::dvec3&) { return value; }), 8);
  for (const Rgb& texel : coarse.radiance)
  {
    // To the rounding of sums of 16 x 16 products.
    EXPECT_LT(relativeError(texel, value), 1e-14);
  }
}

TEST(Downsampled, RefusesWidthsThatAreNotEvenDivisors)
{
  const EnvironmentMap map = mapOf(64, 32, [](const glm::dvec3&) { return Rgb(1.0); });
  for (const int width : { 0, 1, 6, 48, 128 })
  {
    EXPECT_THROW(downsampled(map, width), std::invalid_argument) << width;
  }
  try
  {
    downsampled(map, 6);
  }
  catch (const std::invalid_argument& error)
  {
    EXPECT_STREQ(error.what(), "downsampled: width 6 must be an even divisor of the map's width 64 and at least 2");
  }
  EXPECT_THROW(downsampled(mapOf(64, 64, [](const glm::dvec3&) { return Rgb(1.0); }), 32), std::invalid_argument);
}

// --- The bundled map, read ---------------------------------------------------------------

Rgb meanRadiance(const EnvironmentMap& map)
{
  Rgb sum(0.0);
  for (const Rgb& texel : map.radiance)
  {
    sum += texel;
  }
  return sum / static_cast<double>(map.radiance.size());
}

TEST(ReadEnvironmentMap, VeniceSunset)
{
  const EnvironmentMap hdr = readEnvironmentMap(venicePath + ".hdr");
  ASSERT_EQ(hdr.width, 1024);
  ASSERT_EQ(hdr.height, 512);
  double peak = 0.0;
  for (const Rgb& texel : hdr.radiance)
  {
    peak = std::max(peak, largestComponent(texel));
  }
  EXPECT_NEAR(peak, 6496.0, 0.01 * 6496.0); // the sun (data/PROVENANCE.md)

  const EnvironmentMap exr = readEnvironmentMap(venicePath + ".exr");
  ASSERT_EQ(exr.width, 1024);
  ASSERT_EQ(exr.height, 512);
  EXPECT_LT(relativeError(meanRadiance(exr), meanRadiance(hdr)), 0.01);
}

// --- Spherical harmonics --------------------------------------------------------------------

TEST(SphericalHarmonics, ConstantsAgreeWithThePublishedTable)
{
  // R&H eq. 10 and 13 give them to 6 digits: our closed forms must round to those.
  const double tolerance = 5e-7;
  const std::array<double, 9> atZ = shBasis9({ 0, 0, 1 });
  EXPECT_DOUBLE_EQ(atZ[0], 1.0 / std::sqrt(4.0 * pi));
  EXPECT_DOUBLE_EQ(atZ[2], std::sqrt(3.0 / (4.0 * pi)));
  EXPECT_DOUBLE_EQ(atZ[6], 2.0 * std::sqrt(5.0 / (16.0 * pi)));
  EXPECT_NEAR(atZ[0], 0.282095, tolerance);
  EXPECT_NEAR(atZ[2], 0.488603, tolerance);         // Y10 = 0.488603 z
  EXPECT_NEAR(atZ[6], 2 * 0.315392, 2 * tolerance); // Y20 = 0.315392 (3 z^2 - 1)
  const std::array<double, 9> atX = shBasis9({ 1, 0, 0 });
  EXPECT_NEAR(atX[8], 0.546274, tolerance); // Y22 = 0.546274 (x^2 - y^2)
  EXPECT_DOUBLE_EQ(atX[8], std::sqrt(15.0 / (16.0 * pi)));
  const std::array<double, 9> atXy = shBasis9({ std::sqrt(0.5), std::sqrt(0.5), 0 });
  EXPECT_NEAR(atXy[4], 1.092548 / 2, tolerance); // Y2-2 = 1.092548 xy
  EXPECT_DOUBLE_EQ(atXy[4], std::sqrt(15.0 / (4.0 * pi)) / 2);

  // Eq. 13 with one unit coefficient at a time picks out c1..c5. R&H computed them from the
  // rounded basis constants, so their c2 and c3 are off the closed forms (0.5116634,
  // 0.7431239) by 6e-7 and 1.1e-6.
  const auto irradianceOfUnit = [](int k, const glm::dvec3& n)
  {
    ShCoefficients9 unit;
    unit.fill(Rgb(0.0));
    unit[k] = Rgb(1.0);
    return irradianceFromSh9(unit, n).r;
  };
  const double c5 = -irradianceOfUnit(6, { 1, 0, 0 });
  EXPECT_NEAR(irradianceOfUnit(8, { 1, 0, 0 }), 0.429043, tolerance);   // c1
  EXPECT_NEAR(irradianceOfUnit(3, { 1, 0, 0 }) / 2, 0.511664, 1.5e-6);  // c2
  EXPECT_NEAR(irradianceOfUnit(6, { 0, 0, 1 }) + c5, 0.743125, 1.5e-6); // c3
  EXPECT_NEAR(irradianceOfUnit(0, { 0, 1, 0 }), 0.886227, tolerance);   // c4
  EXPECT_NEAR(c5, 0.247708, tolerance);
}

std::vector<glm::dvec3> testNormals()
{
  std::vector<glm::dvec3> normals = { { 1, 0, 0 }, { -1, 0, 0 }, { 0, 1, 0 }, { 0, -1, 0 }, { 0, 0, 1 }, { 0, 0, -1 } };
  std::mt19937_64 random(7);
  for (int i = 0; i < 20; ++i)
  {
    normals.push_back(randomDirection(random));
  }
  return normals;
}

TEST(SphericalHarmonics, ConstantMapGivesPiL)
{
  // Not exact, though the basis constants are: the projection is a sum at texel centres,
  // which integrates x^2, y^2 and z^2 over the sphere with an error of order h^2, h = pi / H.
  // Summing the rows in closed form (sum of sin((2j + 1) a) = sin^2(H a) / sin(a)) gives a
  // relative error in E of (30 n_y^2 - 10) h^2 / 384 to leading order: at most 4.9e-7 for
  // H = 1024 (2e-6 for H = 512).
  const int height = 1024;
  const Rgb value(0.5, 1.0, 2.0);
  const ShCoefficients9 sh = projectRadiance(mapOf(2 * height, height, [&](const glm::dvec3&) { return value; }));
  const double h = pi / height;
  for (const glm::dvec3& n : testNormals())
  {
    const Rgb irradiance = irradianceFromSh9(sh, n);
    EXPECT_LT(relativeError(irradiance, pi * value), 1e-6) << n.x << " " << n.y << " " << n.z;
    EXPECT_NEAR(irradiance.g / (pi * value.g) - 1.0, (30.0 * n.y * n.y - 10.0) * h * h / 384.0, 1e-10);
  }
}

TEST(SphericalHarmonics, LinearRadianceGivesExactIrradiance)
{
  // L(w) = a + b.w lies in bands 0 and 1, which the 9 coefficients hold exactly. The
  // constant gives pi a. For b.w, split b into (b.n) n and a part perpendicular to n, whose
  // integral against max(0, n.w) vanishes by symmetry about n; the integral of cos^2 over
  // the hemisphere around n is 2 pi / 3. So E(n) = pi a + (2 pi / 3) b.n.
  const Rgb a(3.0, 2.0, 4.0);
  const glm::dvec3 bRed(1.0, -0.5, 0.7);
  const glm::dvec3 bGreen(0.2, 1.5, -0.3);
  const glm::dvec3 bBlue(-1.0, 0.4, 2.0);
  const auto radiance = [&](const glm::dvec3& w)
  { return a + Rgb(glm::dot(bRed, w), glm::dot(bGreen, w), glm::dot(bBlue, w)); };
  const ShCoefficients9 sh = projectRadiance(mapOf(1024, 512, radiance));
  for (const glm::dvec3& n : testNormals())
  {
    const Rgb exact = pi * a + (2.0 * pi / 3.0) * Rgb(glm::dot(bRed, n), glm::dot(bGreen, n), glm::dot(bBlue, n));
    EXPECT_LT(relativeError(irradianceFromSh9(sh, n), exact), 1e-5) << n.x << " " << n.y << " " << n.z;
  }
}

TEST(SphericalHarmonics, SingleBrightTexelWithinThePublishedBound)
{
  // The worst case of R&H: one small bright source. Its projection is exact, so the SH
  // irradiance at cos(gamma) = n.w is L Omega (1/4 + cos/2 + (5/32)(3 cos^2 - 1)) (the
  // addition theorem), off the true L Omega max(0, cos) by at most 3/32 = 9.375% of the peak
  // L Omega, at the horizon (docs/formulas.md section 12.5: about +9.4%).
  EnvironmentMap map = mapOf(64, 32, [](const glm::dvec3&) { return Rgb(0.0); });
  const int column = 40;
  const int row = 10;
  map.radiance[row * map.width + column] = Rgb(1000.0);
  const glm::dvec3 w = texelCentreDirection(map, column, row);
  const double peak = 1000.0 * texelSolidAngle(row, map.width, map.height);
  const ShCoefficients9 sh = projectRadiance(map);

  std::vector<glm::dvec3> normals = testNormals();
  const glm::dvec3 horizon = unitVector(glm::cross(w, glm::dvec3(0, 1, 0)));
  for (const glm::dvec3& n : { w, -w, horizon, unitVector(w + horizon), unitVector(horizon - w) })
  {
    normals.push_back(n);
  }
  double largestError = 0.0;
  for (const glm::dvec3& n : normals)
  {
    const double exact = peak * std::max(0.0, glm::dot(n, w));
    largestError = std::max(largestError, std::abs(irradianceFromSh9(sh, n).r - exact) / peak);
  }
  std::cout << "single bright texel: largest SH irradiance error " << 100.0 * largestError
            << "% of the peak irradiance\n";
  EXPECT_NEAR(largestError, 3.0 / 32.0, 1e-9);
  EXPECT_LT(largestError, 0.10);
}

TEST(SphericalHarmonics, ProjectionTimeOf1024x512)
{
  const EnvironmentMap map = readEnvironmentMap(venicePath + ".hdr");
  double fastest = std::numeric_limits<double>::infinity();
  double slowest = 0.0;
  ShCoefficients9 sh;
  for (int run = 0; run < 5; ++run)
  {
    const auto start = std::chrono::steady_clock::now();
    sh = projectRadiance(map);
    const std::chrono::duration<double, std::milli> elapsed = std::chrono::steady_clock::now() - start;
    fastest = std::min(fastest, elapsed.count());
    slowest = std::max(slowest, elapsed.count());
  }
  std::cout << "projectRadiance of 1024x512: " << fastest << " ms fastest, " << slowest << " ms slowest of 5 runs\n";
  // Band 0 is the mean radiance over the sphere times 4 pi Y00.
  EXPECT_LT(relativeError(sh[0], radiantIntegral(map) * 0.5 / std::sqrt(pi)), 1e-12);
}

TEST(SphericalHarmonics, TheBasisIsOrthonormalToBandFour)
{
  // A product of two functions of band 4 or less has degree 8 at most, which the rule
  // integrates exactly.
  const std::vector<SphereNode> nodes = sphereQuadrature(2 * largestShOrder);
  double areaSum = 0;
  for (const SphereNode& node : nodes)
  {
    areaSum += node.weight;
    EXPECT_NEAR(glm::length(node.direction), 1.0, 1e-15);
  }
  EXPECT_NEAR(areaSum, 4 * pi, 1e-13);
  for (int i = 0; i < shCount(largestShOrder); ++i)
  {
    for (int j = 0; j < shCount(largestShOrder); ++j)
    {
      double product = 0;
      for (const SphereNode& node : nodes)
      {
        const ShBasis y = shBasis(largestShOrder, node.direction);
        product += node.weight * y[i] * y[j];
      }
      ASSERT_NEAR(product, i == j ? 1.0 : 0.0, 1e-13) << i << " " << j;
    }
  }
}

TEST(SphericalHarmonics, BandsThreeAndFourAreTheirClosedForms)
{
  // The real harmonics' Cartesian forms (as tabulated, e.g., in Sloan's "Stupid Spherical
  // Harmonics Tricks", 2008, appendix A2, there with the Condon-Shortley phase on odd m), at
  // directions away from the axes.
  std::mt19937_64 random(11);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 20; ++trial)
  {
    const glm::dvec3 w = glm::normalize(glm::dvec3(normal(random), normal(random), normal(random)));
    const double x = w.x, y = w.y, z = w.z;
    const ShBasis basis = shBasis(4, w);
    EXPECT_NEAR(basis[shIndex(3, -3)], 0.25 * std::sqrt(35 / (2 * pi)) * y * (3 * x * x - y * y), 1e-14);
    EXPECT_NEAR(basis[shIndex(3, 0)], 0.25 * std::sqrt(7 / pi) * z * (5 * z * z - 3), 1e-14);
    EXPECT_NEAR(basis[shIndex(3, 3)], 0.25 * std::sqrt(35 / (2 * pi)) * x * (x * x - 3 * y * y), 1e-14);
    EXPECT_NEAR(basis[shIndex(4, -4)], 0.75 * std::sqrt(35 / pi) * x * y * (x * x - y * y), 1e-14);
    EXPECT_NEAR(basis[shIndex(4, 0)], 3 / (16 * std::sqrt(pi)) * (35 * z * z * z * z - 30 * z * z + 3), 1e-14);
    EXPECT_NEAR(basis[shIndex(4, 2)], 0.375 * std::sqrt(5 / pi) * (x * x - y * y) * (7 * z * z - 1), 1e-14);
    // Bands 0 to 2: R&H's eq. 10, to rounding.
    const double c1 = std::sqrt(3 / (4 * pi)), c2 = std::sqrt(15 / (4 * pi));
    const std::array<double, 9> eq10 = { 0.5 / std::sqrt(pi), c1 * y, c1 * z, c1 * x, c2 * x * y, c2 * y * z,
      std::sqrt(5 / (16 * pi)) * (3 * z * z - 1), c2 * x * z, std::sqrt(15 / (16 * pi)) * (x * x - y * y) };
    const std::array<double, 9> nine = shBasis9(w);
    for (int k = 0; k < 9; ++k)
    {
      EXPECT_NEAR(nine[k], eq10[k], 1e-15) << k;
    }
    EXPECT_EQ(shBasis(2, w)[shIndex(3, 0)], 0.0) << "past the order, 0";
  }
}

TEST(SphericalHarmonics, TheClampedCosinesBandsAreItsLegendreIntegrals)
{
  // A_l = 2 pi times the integral over t in [0, 1] of t P_l(t) (Funk-Hecke), here by Simpson's
  // rule on the Legendre polynomials written out, against the closed form.
  const std::function<double(double)> legendre[] = { [](double) { return 1.0; }, [](double t) { return t; },
    [](double t) { return (3 * t * t - 1) / 2; }, [](double t) { return (5 * t * t * t - 3 * t) / 2; },
    [](double t) { return (35 * t * t * t * t - 30 * t * t + 3) / 8; } };
  for (int l = 0; l <= 4; ++l)
  {
    const int steps = 1000;
    double sum = 0;
    for (int k = 0; k <= steps; ++k)
    {
      const double t = double(k) / steps;
      sum += (k == 0 || k == steps ? 1 : k % 2 == 1 ? 4 : 2) * t * legendre[l](t);
    }
    // Simpson's error, (h^4 / 180) times the largest fourth derivative, is below 1e-11 here.
    EXPECT_NEAR(clampedCosineBand(l), 2 * pi * sum / (3.0 * steps), 1e-10) << l;
  }
  EXPECT_DOUBLE_EQ(clampedCosineBand(0), pi);
  EXPECT_DOUBLE_EQ(clampedCosineBand(2), pi / 4);
  EXPECT_EQ(clampedCosineBand(3), 0.0);
  EXPECT_DOUBLE_EQ(clampedCosineBand(4), -pi / 24);
  EXPECT_THROW(projectRadiance(mapOf(8, 4, [](const glm::dvec3&) { return Rgb(1.0); }), 5), std::invalid_argument);
}

TEST(ShRotation, TurningTheCoefficientsTurnsTheRadiance)
{
  // A radiance of bands 0 to 4 with random coefficients: the turned coefficients' radiance at a
  // direction w is the radiance at r^T w, for rotations about every axis and their products.
  std::mt19937_64 random(5);
  std::normal_distribution<double> normal;
  ShCoefficients coefficients(shCount(4));
  for (Rgb& c : coefficients)
  {
    c = Rgb(normal(random), normal(random), normal(random));
  }
  auto radianceAt = [](const ShCoefficients& c, const glm::dvec3& w)
  {
    const ShBasis basis = shBasis(4, w);
    Rgb sum(0.0);
    for (std::size_t k = 0; k < c.size(); ++k)
    {
      sum += c[k] * basis[k];
    }
    return sum;
  };
  for (int trial = 0; trial < 10; ++trial)
  {
    const glm::dvec3 axis = glm::normalize(glm::dvec3(normal(random), normal(random), normal(random)));
    const glm::dmat3 r = glm::dmat3(glm::rotate(glm::dmat4(1.0), normal(random) * 2, axis));
    const ShCoefficients turned = ShRotation(4, r)(coefficients);
    for (int k = 0; k < 10; ++k)
    {
      const glm::dvec3 w = glm::normalize(glm::dvec3(normal(random), normal(random), normal(random)));
      const Rgb expected = radianceAt(coefficients, glm::transpose(r) * w);
      const Rgb got = radianceAt(turned, w);
      for (int c = 0; c < 3; ++c)
      {
        ASSERT_NEAR(got[c], expected[c], 1e-12 * (1 + std::abs(expected[c])));
      }
    }
  }
  EXPECT_THROW(ShRotation(2, glm::dmat3(1.0))(coefficients), std::invalid_argument) << "25 coefficients for order 2";
  EXPECT_THROW(ShRotation(5, glm::dmat3(1.0)), std::invalid_argument);
}

TEST(ShRotation, TurningAMapsNineCoefficientsIsTurningItsIrradiance)
{
  // The SH estimator turns its irradiance polynomial (composedWith); turning the coefficients
  // instead gives the same irradiance: a map of a bright patch, turned 70 degrees about +y.
  const EnvironmentMap map =
    mapOf(128, 64, [](const glm::dvec3& w) { return Rgb(w.x > 0.6 ? 5.0 : 0.2, 1.0, w.y > 0 ? 2.0 : 0.5); });
  const ShCoefficients9 nine = projectRadiance(map);
  const double angle = glm::radians(70.0);
  const glm::dmat3 r = glm::dmat3(glm::rotate(glm::dmat4(1.0), angle, glm::dvec3(0, 1, 0)));
  const ShCoefficients turned = ShRotation(2, r)(ShCoefficients(nine.begin(), nine.end()));
  ShCoefficients9 turnedNine;
  std::copy(turned.begin(), turned.end(), turnedNine.begin());
  const IrradiancePolynomial composed = composedWith(irradiancePolynomial(nine), glm::transpose(r));
  for (const glm::dvec3& n : { glm::dvec3(1, 0, 0), glm::dvec3(0, 0, 1), glm::normalize(glm::dvec3(1, 2, -3)) })
  {
    const Rgb a = irradianceFromSh9(turnedNine, n), b = composed(n);
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_NEAR(a[c], b[c], 1e-12 * std::abs(b[c]));
    }
  }
}

// --- Importance sampling --------------------------------------------------------------------

/// The cumulative distribution of weights, from 0 to 1, as the sampler builds it.
std::vector<double> cumulativeDistribution(const std::vector<double>& weights)
{
  std::vector<double> cdf(weights.size() + 1, 0.0);
  for (std::size_t i = 0; i < weights.size(); ++i)
  {
    cdf[i + 1] = cdf[i] + weights[i];
  }
  const double sum = cdf.back();
  for (double& value : cdf)
  {
    value /= sum;
  }
  return cdf;
}

struct BinAndOffset
{
  int bin;
  double offset;
};

/// The bin of a cdf of `bins` bins that holds u, by std::upper_bound, and where in it.
BinAndOffset invertedAt(const double* cdf, int bins, double u)
{
  const int bin = static_cast<int>(std::upper_bound(cdf, cdf + bins + 1, u) - cdf) - 1;
  return { bin, (u - cdf[bin]) / (cdf[bin + 1] - cdf[bin]) };
}

/// A smooth, coloured map: a soft bright lobe around d on a dim sky.
EnvironmentMap smoothMap(int width)
{
  const glm::dvec3 d = unitVector(glm::dvec3(0.6, 0.5, -0.4));
  return mapOf(width, width / 2,
    [&](const glm::dvec3& w)
    {
      const double lobe = std::exp(8.0 * (glm::dot(w, d) - 1.0));
      return Rgb(0.2, 0.3, 0.5) + Rgb(20.0, 15.0, 8.0) * lobe;
    });
}

TEST(EnvironmentSampler, PdfIntegratesToOne)
{
  // Not exactly 1: the density per solid angle at a texel centre is uniform over the texel
  // only to first order, and the sum is 2 H sin(pi / 2H) / pi = 1 - (pi / 2H)^2 / 6, 1 - 1e-4
  // for H = 64.
  for (const EnvironmentMap& map : { smoothMap(128), downsampled(readEnvironmentMap(venicePath + ".hdr"), 256) })
  {
    const EnvironmentSampler sampler(map);
    double sum = 0.0;
    for (int row = 0; row < map.height; ++row)
    {
      for (int column = 0; column < map.width; ++column)
      {
        sum += sampler.pdf(texelCentreDirection(map, column, row)) * texelSolidAngle(row, map.width, map.height);
      }
    }
    EXPECT_NEAR(sum, 1.0, 1e-3) << map.width;
  }
}

TEST(EnvironmentSampler, PdfOfASampleIsTheSamplesPdf)
{
  const EnvironmentMap map = downsampled(readEnvironmentMap(venicePath + ".hdr"), 256);
  const EnvironmentSampler sampler(map);
  std::mt19937_64 random(8);
  std::uniform_real_distribution<double> uniform;
  for (int i = 0; i < 10000; ++i)
  {
    const EnvironmentSample s = sampler.sample(uniform(random), uniform(random));
    EXPECT_NEAR(glm::length(s.direction), 1.0, 1e-15);
    ASSERT_GT(s.pdf, 0.0);
    EXPECT_NEAR(sampler.pdf(s.direction), s.pdf, 1e-9 * s.pdf);
    const glm::dvec2 uv = uvOfDirection(s.direction);
    EXPECT_EQ(s.radiance, map.texel(static_cast<int>(uv.x * map.width), static_cast<int>(uv.y * map.height)));
    EXPECT_GT(luminance(s.radiance), 0.0);
  }
}

TEST(EnvironmentSampler, DrawsTheTexelThatABinarySearchOfItsDistributionDraws)
{
  // The sampler finds a sample's row and column through guide tables. Here the same
  // distribution is built again and searched with std::upper_bound: every u, on a grid and on
  // the bins' own edges, must give the same texel. Black texels and a black row make bins of
  // zero width, which no u may land in.
  EnvironmentMap map{ 16, 8, {} };
  for (int row = 0; row < map.height; ++row)
  {
    for (int column = 0; column < map.width; ++column)
    {
      const bool black = row == 3 || (column + row) % 5 == 0;
      map.radiance.push_back(black ? Rgb(0.0) : Rgb(1.0 + column + 16.0 * row, 0.5, 0.25 * column));
    }
  }
  const EnvironmentSampler sampler(map);
  // The distribution as the sampler builds it: luminance times the row centre's sine, summed.
  std::vector<std::vector<double>> columnCdfs;
  std::vector<double> rowWeights;
  for (int row = 0; row < map.height; ++row)
  {
    std::vector<double> weights;
    for (int column = 0; column < map.width; ++column)
    {
      weights.push_back(luminance(map.texel(column, row)) * std::sin(pi * (row + 0.5) / map.height));
    }
    rowWeights.push_back(std::accumulate(weights.begin(), weights.end(), 0.0));
    columnCdfs.push_back(row == 3 ? std::vector<double>() : cumulativeDistribution(weights));
  }
  const std::vector<double> rowCdf = cumulativeDistribution(rowWeights);
  auto binOf = [](const std::vector<double>& cdf, double u)
  { return invertedAt(cdf.data(), static_cast<int>(cdf.size()) - 1, u).bin; };
  std::vector<double> us;
  for (int i = 0; i < 4001; ++i)
  {
    us.push_back(i / 4001.0);
  }
  us.insert(us.end(), rowCdf.begin(), rowCdf.end() - 1);
  us.insert(us.end(), columnCdfs[0].begin(), columnCdfs[0].end() - 1);
  // A trailing black texel puts an inner edge at 1, which is no sample's u.
  us.erase(std::remove_if(us.begin(), us.end(), [](double u) { return u >= 1.0; }), us.end());
  int drawn = 0;
  for (const double u2 : us)
  {
    const int row = binOf(rowCdf, u2);
    ASSERT_NE(row, 3) << "u2 " << u2;
    for (const double u1 : us)
    {
      const int column = binOf(columnCdfs[row], u1);
      EXPECT_EQ(sampler.sample(u1, u2).radiance, map.texel(column, row)) << "u " << u1 << ", " << u2;
      ++drawn;
    }
  }
  EXPECT_GT(drawn, 16000000);
}

TEST(EnvironmentSampler, MonteCarloIrradianceAgreesWithTheTexelSum)
{
  const EnvironmentMap map = smoothMap(128);
  const EnvironmentSampler sampler(map);
  std::mt19937_64 random(9);
  std::uniform_real_distribution<double> uniform;
  const int count = 4096;
  for (const glm::dvec3& n : testNormals())
  {
    Rgb sum(0.0);
    Rgb sumOfSquares(0.0);
    for (int i = 0; i < count; ++i)
    {
      const EnvironmentSample s = sampler.sample(uniform(random), uniform(random));
      const Rgb estimate = s.radiance * std::max(0.0, glm::dot(n, s.direction)) / s.pdf;
      sum += estimate;
      sumOfSquares += estimate * estimate;
    }
    const Rgb mean = sum / double(count);
    const Rgb variance = (sumOfSquares / double(count) - mean * mean) * (count / (count - 1.0));
    const Rgb standardError = glm::sqrt(variance / double(count));
    const Rgb exact = bruteForceIrradiance(map, n);
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_LE(std::abs(mean[c] - exact[c]), 5.0 * standardError[c])
        << "channel " << c << " normal " << n.x << " " << n.y << " " << n.z;
    }
  }
}

TEST(EnvironmentSampler, DirectionsDrawnTogetherAreTheDirectionsDrawnOneByOne)
{
  // sampleDirections draws every row of a batch first, fetching the columns' tables ahead:
  // the directions must be sample's, bit for bit, for any count (batches of 16 and a part),
  // on a map with light, with black texels, and on a black map (no tables).
  std::mt19937_64 random(12);
  std::uniform_real_distribution<double> uniform;
  for (const EnvironmentMap& map :
    { mapOf(64, 32, [](const glm::dvec3& w) { return Rgb(w.x > 0.5 ? 0.0 : 1.0 + w.y, 0.5, 2.0); }),
      mapOf(16, 8, [](const glm::dvec3&) { return Rgb(0.0); }) })
  {
    const EnvironmentSampler sampler(map);
    for (int count : { 0, 1, 16, 37 })
    {
      std::vector<double> u1(std::size_t(count) + 1), u2(std::size_t(count) + 1);
      for (int k = 0; k < count; ++k)
      {
        u1[std::size_t(k)] = k == 0 ? 0.0 : uniform(random); // an edge as well
        u2[std::size_t(k)] = uniform(random);
      }
      std::vector<glm::dvec3> together(std::size_t(count) + 1, glm::dvec3(-7.0));
      sampler.sampleDirections(count, u1.data(), u2.data(), together.data());
      // samples() and at() for many: the bits of sample() and at() for one.
      const EnvironmentSample unwritten{ glm::dvec3(-7.0), -7.0, Rgb(-7.0) };
      std::vector<EnvironmentSample> samples(std::size_t(count) + 1, unwritten), there(samples);
      sampler.samples(count, u1.data(), u2.data(), samples.data());
      std::vector<glm::dvec3> elsewhere(std::size_t(count) + 1);
      for (glm::dvec3& direction : elsewhere)
      {
        direction = randomDirection(random);
      }
      sampler.at(count, elsewhere.data(), there.data());
      for (int k = 0; k < count; ++k)
      {
        const std::size_t i = std::size_t(k);
        const EnvironmentSample alone = sampler.sample(u1[i], u2[i]);
        EXPECT_EQ(together[i], alone.direction) << "sample " << k << " of " << count;
        EXPECT_EQ(samples[i].direction, alone.direction) << "sample " << k << " of " << count;
        EXPECT_EQ(samples[i].pdf, alone.pdf) << "sample " << k << " of " << count;
        EXPECT_EQ(samples[i].radiance, alone.radiance) << "sample " << k << " of " << count;
        const EnvironmentSample atAlone = sampler.at(elsewhere[i]);
        EXPECT_EQ(there[i].direction, atAlone.direction);
        EXPECT_EQ(there[i].pdf, atAlone.pdf);
        EXPECT_EQ(there[i].radiance, atAlone.radiance);
      }
      // Nothing written past count.
      EXPECT_EQ(together[std::size_t(count)], glm::dvec3(-7.0));
      EXPECT_EQ(samples[std::size_t(count)].pdf, -7.0);
      EXPECT_EQ(there[std::size_t(count)].pdf, -7.0);
    }
  }
}

TEST(EnvironmentSampler, DirectionsAreDirectionAtOfTheTexelAndTheOffsetDrawn)
{
  // On a map of 128 x 64 texels or more, a sample's direction is found from tables of each
  // row's and column's edge and series for the offset into the texel, not by directionAt's
  // sine and cosine. Here the texel and the offsets are found again by inverting the map's
  // distribution with std::upper_bound, and directionAt of them must agree to a few roundings.
  for (const EnvironmentMap& map : { smoothMap(128), downsampled(readEnvironmentMap(venicePath + ".hdr"), 256) })
  {
    const EnvironmentSampler sampler(map);
    std::vector<double> rowWeights, columnCdfs;
    for (int row = 0; row < map.height; ++row)
    {
      std::vector<double> weights;
      for (int column = 0; column < map.width; ++column)
      {
        weights.push_back(luminance(map.texel(column, row)) * std::sin(pi * (row + 0.5) / map.height));
      }
      rowWeights.push_back(std::accumulate(weights.begin(), weights.end(), 0.0));
      const std::vector<double> cdf = cumulativeDistribution(weights);
      columnCdfs.insert(columnCdfs.end(), cdf.begin(), cdf.end());
    }
    const std::vector<double> rowCdf = cumulativeDistribution(rowWeights);
    std::mt19937_64 random(13);
    std::uniform_real_distribution<double> uniform;
    double largest = 0;
    for (int i = 0; i < 20000; ++i)
    {
      const double u1 = uniform(random), u2 = uniform(random);
      const BinAndOffset row = invertedAt(rowCdf.data(), map.height, u2);
      const BinAndOffset column = invertedAt(&columnCdfs[std::size_t(row.bin) * (map.width + 1)], map.width, u1);
      const glm::dvec3 expected =
        directionAt((column.bin + column.offset) / map.width, (row.bin + row.offset) / map.height);
      largest = std::max(largest, glm::length(sampler.sampleDirection(u1, u2) - expected));
    }
    EXPECT_LT(largest, 1e-15) << map.width;
    EXPECT_GT(largest, 0.0) << map.width; // not directionAt's own bits: the tables are used
  }
}

TEST(EnvironmentSampler, BlackMapIsSampledUniformly)
{
  const EnvironmentSampler sampler(mapOf(16, 8, [](const glm::dvec3&) { return Rgb(0.0); }));
  std::mt19937_64 random(10);
  std::uniform_real_distribution<double> uniform;
  for (int i = 0; i < 1000; ++i)
  {
    const double u2 = uniform(random);
    const EnvironmentSample s = sampler.sample(uniform(random), u2);
    EXPECT_DOUBLE_EQ(s.pdf, 1.0 / (4.0 * pi));
    EXPECT_NEAR(s.direction.y, 1.0 - 2.0 * u2, 1e-12); // uniform height: uniform area
    EXPECT_EQ(s.radiance, Rgb(0.0));
    EXPECT_DOUBLE_EQ(sampler.pdf(randomDirection(random)), 1.0 / (4.0 * pi));
  }
}

TEST(EnvironmentSampler, SamplesOnlyTexelsWithRadiance)
{
  EnvironmentMap map = mapOf(16, 8, [](const glm::dvec3&) { return Rgb(0.0); });
  map.radiance[3 * 16 + 5] = Rgb(0.0, 0.0, 2.0);
  map.radiance[6 * 16 + 12] = Rgb(1.0, 0.0, 0.0);
  const EnvironmentSampler sampler(map);
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> uniform;
  for (int i = 0; i < 1000; ++i)
  {
    EXPECT_NE(sampler.sample(uniform(random), uniform(random)).radiance, Rgb(0.0));
  }
  EXPECT_EQ(sampler.pdf(texelCentreDirection(map, 0, 0)), 0.0);
  EXPECT_GT(sampler.pdf(texelCentreDirection(map, 5, 3)), 0.0);
  EXPECT_GT(sampler.pdf(texelCentreDirection(map, 12, 6)), 0.0);
}

TEST(EnvironmentSampler, RefusesNegativeRadiance)
{
  EnvironmentMap map = mapOf(8, 4, [](const glm::dvec3&) { return Rgb(1.0); });
  map.radiance[9] = Rgb(1.0, -0.1, 1.0);
  EXPECT_THROW(EnvironmentSampler{ map }, std::invalid_argument);
}
}
