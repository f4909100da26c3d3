// Precomputed radiance transfer (docs/formulas.md sections 12.9 and 12.10): the unshadowed
// transfer against R&H's nine coefficients, the shadowed one against closed forms, and the
// "prt" estimator against the "sh" and brute-force ones, turned and not.
#include "EnvironmentLightEstimator.h"
#include "PolygonIrradiance.h"
#include "RadianceTransfer.h"
#include "SampleSequence.h"
#include "SampleWarps.h"
#include "TestPaths.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

namespace
{
using namespace shadelab;
constexpr double pi = 3.14159265358979323846;

TEST(RadianceTransfer, TheUnshadowedTransferOfOrderTwoIsTheNineCoefficientsIrradiance)
{
  // A map of random radiances: the dot product of its nine coefficients with the transfer at a
  // normal is R&H's polynomial there, to rounding.
  EnvironmentMap map;
  map.width = 64;
  map.height = 32;
  std::mt19937_64 random(3);
  std::uniform_real_distribution<double> uniform(0, 4);
  for (int k = 0; k < map.width * map.height; ++k)
  {
    map.radiance.push_back(Rgb(uniform(random), uniform(random), uniform(random)));
  }
  const ShCoefficients coefficients = projectRadiance(map, 2);
  const ShCoefficients9 nine = projectRadiance(map);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 50; ++trial)
  {
    const glm::dvec3 n = glm::normalize(glm::dvec3(normal(random), normal(random), normal(random)));
    const Rgb transferred = irradianceFromTransfer(coefficients, unshadowedTransfer(2, n));
    const Rgb polynomial = irradianceFromSh9(nine, n);
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_NEAR(transferred[c], polynomial[c], 1e-13 * std::abs(polynomial[c]));
    }
  }
  // Band 3's factor is 0: order 3 adds nothing; order 4 adds band 4's.
  const glm::dvec3 n = glm::normalize(glm::dvec3(1, 2, 3));
  const TransferVector three = unshadowedTransfer(3, n), two = unshadowedTransfer(2, n);
  for (int k = 0; k < shCount(3); ++k)
  {
    EXPECT_EQ(three[k], k < shCount(2) ? two[k] : 0.0) << k;
  }
}

/// Cosine-weighted stratified directions about n for a vertex, as a light's samples are drawn.
template<typename Visible>
TransferEstimate estimated(int order, const glm::dvec3& n, int samples, std::uint64_t vertex, Visible&& visible)
{
  Sampling sampling;
  sampling.samples = samples;
  const SampleSequence sequence(7, vertex, sampling);
  TransferEstimate estimate(order, true);
  for (int j = 0; j < samples; ++j)
  {
    const glm::dvec3 w = cosineWeightedDirection(n, sequence.point(j)).direction;
    estimate.add(w, visible(w));
  }
  return estimate;
}

TEST(RadianceTransfer, AnOpenSkysEstimateIsTheUnshadowedTransferWithinItsStandardErrors)
{
  // Every coefficient of bands 0 to 4, at normals all round: within 3 standard errors at 99%
  // of them or more.
  std::mt19937_64 random(9);
  std::normal_distribution<double> normal;
  int within = 0, count = 0;
  for (int trial = 0; trial < 40; ++trial)
  {
    const glm::dvec3 n = glm::normalize(glm::dvec3(normal(random), normal(random), normal(random)));
    const TransferVector exact = unshadowedTransfer(4, n);
    const TransferEstimate estimate = estimated(4, n, 256, trial, [](const glm::dvec3&) { return true; });
    const TransferVector value = estimate.value(), error = estimate.standardError();
    for (int k = 0; k < shCount(4); ++k)
    {
      within += std::abs(value[k] - exact[k]) <= 3 * error[k] + 1e-12 ? 1 : 0;
      ++count;
    }
    EXPECT_NEAR(value[0], exact[0], 1e-12) << "every sample of band 0 is pi Y_00";
  }
  EXPECT_GE(double(within), 0.99 * count) << within << " of " << count;
  // The standard errors follow the samples: 16 times as many cut them at least 4 times
  // (stratified, they fall faster than 1/sqrt(N)).
  const glm::dvec3 n(0.6, 0.0, 0.8);
  auto open = [](const glm::dvec3&) { return true; };
  const TransferVector few = estimated(4, n, 64, 1, open).standardError();
  const TransferVector many = estimated(4, n, 1024, 1, open).standardError();
  for (int k = 1; k < shCount(4); ++k)
  {
    EXPECT_LE(many[k], few[k] / 4) << k;
  }
  EXPECT_THROW(TransferEstimate(5, true), std::invalid_argument);
  EXPECT_THROW(unshadowedTransfer(-1, n), std::invalid_argument);
}

TEST(RadianceTransfer, AConstantSkyOverAnOpenBoxGivesTheOpeningsFormFactorOnTheFloor)
{
  // The box [-1, 1] x [0, 1] x [-1, 1] open at y = 1: from the floor, a direction reaches the
  // sky where it leaves through the opening. A constant radiance L has L_00 = L sqrt(4 pi) and no
  // other coefficient, so E = L sqrt(4 pi) T_00, against L times the opening's projected solid
  // angle (Lambert's formula): within 3 standard errors at 99% of the floor points or more.
  const double radiance = 2;
  const std::vector<glm::dvec3> opening = { { -1, 1, -1 }, { 1, 1, -1 }, { 1, 1, 1 }, { -1, 1, 1 } };
  ShCoefficients sky(shCount(2), Rgb(0.0));
  sky[0] = Rgb(radiance * std::sqrt(4 * pi));
  int within = 0, count = 0;
  double squares = 0;
  for (int i = 0; i < 20; ++i)
  {
    for (int k = 0; k < 20; ++k)
    {
      const glm::dvec3 p(-0.95 + 0.1 * i, 0, -0.95 + 0.1 * k);
      auto throughTheOpening = [&](const glm::dvec3& w)
      {
        const double t = 1 / w.y; // to y = 1 (w.y > 0 for every cosine-weighted direction here)
        const glm::dvec3 top = p + t * w;
        return w.y > 0 && std::abs(top.x) <= 1 && std::abs(top.z) <= 1;
      };
      const TransferEstimate estimate = estimated(2, { 0, 1, 0 }, 256, std::uint64_t(count), throughTheOpening);
      const Rgb e = irradianceFromTransfer(sky, estimate.value());
      const double error = e.x - radiance * polygonProjectedSolidAngle(opening, p, { 0, 1, 0 });
      const double standardError = radiance * std::sqrt(4 * pi) * estimate.standardError()[0];
      within += std::abs(error) <= 3 * standardError ? 1 : 0;
      squares += error * error;
      ++count;
    }
  }
  EXPECT_GE(double(within), 0.99 * count) << within << " of " << count;
  // Below the largest standard deviation of a fraction of 256 independent cosine-weighted rays,
  // pi L sqrt(1/4 / 256).
  EXPECT_LT(std::sqrt(squares / count), pi * radiance / (2 * std::sqrt(256.0)));
}
}

namespace
{
const std::string studioMap = shadelab::testing::sourcePath("data/envmaps/studio_small_03_1k.hdr");
const std::string veniceMap = shadelab::testing::sourcePath("data/envmaps/venice_sunset_1k.hdr");

EnvironmentLight transferLight(const std::string& file, EnvironmentEstimator estimator, int order, double rotation)
{
  EnvironmentLight light;
  light.file = file;
  light.map = std::make_shared<const EnvironmentMap>(readEnvironmentMap(file));
  light.estimator = estimator;
  light.shOrder = order;
  light.rotationDegrees = rotation;
  light.color = Rgb(1.0, 0.8, 0.5);
  light.intensity = 1.5;
  return light;
}

SurfacePoint facing(const glm::dvec3& n)
{
  return { glm::dvec3(0.0), n, n, 0 };
}

std::vector<glm::dvec3> randomNormals(int count, std::uint64_t seed)
{
  std::mt19937_64 random(seed);
  std::normal_distribution<double> normal;
  std::vector<glm::dvec3> normals;
  for (int k = 0; k < count; ++k)
  {
    normals.push_back(glm::normalize(glm::dvec3(normal(random), normal(random), normal(random))));
  }
  return normals;
}
}

TEST(RadianceTransfer, TheTruncatedCosineErrsMostAtTheHorizon)
{
  // max(0, t) less its Legendre series to band N, scanned over [-1, 1]: never above the peak
  // the bound charges, which is reached at t = 0.
  EXPECT_DOUBLE_EQ(clampedCosineTruncationPeak(2), 3.0 / 32);
  EXPECT_DOUBLE_EQ(clampedCosineTruncationPeak(3), 3.0 / 32);
  EXPECT_DOUBLE_EQ(clampedCosineTruncationPeak(4), 15.0 / 256);
  for (int order = 2; order <= largestShOrder; ++order)
  {
    double largest = 0;
    for (int step = 0; step <= 200000; ++step)
    {
      const double t = -1 + step / 100000.0;
      double previous = 1, legendre = t, series = clampedCosineBand(0) / (4 * pi);
      for (int l = 1; l <= order; ++l)
      {
        series += clampedCosineBand(l) * (2 * l + 1) / (4 * pi) * legendre;
        const double next = ((2 * l + 1) * t * legendre - l * previous) / (l + 1); // Bonnet's recursion
        previous = legendre;
        legendre = next;
      }
      largest = std::max(largest, std::abs(series - std::max(0.0, t)));
    }
    EXPECT_NEAR(largest, clampedCosineTruncationPeak(order), 1e-15) << order;
  }
  EXPECT_THROW(clampedCosineTruncationPeak(1), std::invalid_argument);
  EXPECT_THROW(clampedCosineTruncationPeak(5), std::invalid_argument);
}

TEST(RadianceTransfer, OrderTwoWithoutShadowsIsTheShEstimatorToRounding)
{
  // The same nine coefficients, one way dotted with A_l Y_lm(n) after turning them into the
  // world, the other R&H's polynomial composed with the turn: the same irradiance to rounding.
  const EnvironmentLightEstimator sh(transferLight(studioMap, EnvironmentEstimator::SphericalHarmonics, 2, 37), 0, {});
  const EnvironmentLightEstimator prt(
    transferLight(studioMap, EnvironmentEstimator::PrecomputedTransfer, 2, 37), 0, {});
  for (const glm::dvec3& n : randomNormals(200, 5))
  {
    const DistributedTerms a = sh.estimate(facing(n)), b = prt.estimate(facing(n));
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_NEAR(b.irradiance[c], a.irradiance[c], 1e-12 * largestComponent(glm::abs(a.irradiance)) + 1e-15);
    }
    const TransferVector transfer = unshadowedTransfer(2, n);
    EXPECT_TRUE(std::equal(transfer.begin(), transfer.end(), b.transfer.begin()));
    EXPECT_EQ(b.transferStdError, TransferVector{});
  }
}

TEST(RadianceTransfer, TurningTheMapTurnsItsCoefficients)
{
  // A map turned by 70 degrees about +y lights the normal n as the unturned map lights R^T n:
  // once through the coefficients turned by ShRotation, once through the normal. And each order
  // is within its band-limit bound of the brute-force sum over every texel.
  const double angle = 70 * pi / 180;
  const glm::dmat3 turn(glm::dvec3(std::cos(angle), 0, -std::sin(angle)), glm::dvec3(0, 1, 0),
    glm::dvec3(std::sin(angle), 0, std::cos(angle)));
  EnvironmentLight texels = transferLight(veniceMap, EnvironmentEstimator::BruteForce, 2, 70);
  texels.bruteForceWidth = texels.map->width;
  const EnvironmentLightEstimator exact(texels, 0, {});
  for (int order = 2; order <= largestShOrder; ++order)
  {
    const EnvironmentLight turnedLight = transferLight(veniceMap, EnvironmentEstimator::PrecomputedTransfer, order, 70);
    const EnvironmentLightEstimator turned(turnedLight, 0, {});
    const EnvironmentLightEstimator unturned(
      transferLight(veniceMap, EnvironmentEstimator::PrecomputedTransfer, order, 0), 0, {});
    const double bound =
      largestComponent(turnedLight.color * turnedLight.intensity * shIrradianceErrorBound(*turnedLight.map, order));
    for (const glm::dvec3& n : randomNormals(40, 11 + order))
    {
      const Rgb e = turned.estimate(facing(n)).irradiance;
      const Rgb there = unturned.estimate(facing(glm::transpose(turn) * n)).irradiance;
      const Rgb sum = exact.estimate(facing(n)).irradiance;
      for (int c = 0; c < 3; ++c)
      {
        EXPECT_NEAR(e[c], there[c], 1e-12 * largestComponent(glm::abs(there))) << order;
        EXPECT_LE(std::abs(e[c] - sum[c]), bound) << order;
      }
    }
  }
}
