// The estimators of area lights and environment maps (DistributedLight.h), each pinned to a
// truth: closed forms, the exact formulas, or a brute-force sum, with stated tolerances.
#include "AreaLightEstimator.h"
#include "EnvironmentLightEstimator.h"
#include "EnvironmentMap.h"
#include "LobeSampling.h"
#include "MonteCarloEstimate.h"
#include "PolygonIrradiance.h"
#include "SampleSequence.h"
#include "TestPaths.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <numeric>
#include <random>

using namespace shadelab;

namespace
{
constexpr double pi = 3.14159265358979323846;

/// n roughly even unit vectors over the sphere (the Fibonacci lattice).
std::vector<glm::dvec3> spreadDirections(int n)
{
  std::vector<glm::dvec3> directions;
  const double golden = pi * (3 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i)
  {
    const double y = 1 - 2 * (i + 0.5) / n;
    const double r = std::sqrt(1 - y * y);
    directions.push_back({ r * std::cos(golden * i), y, r * std::sin(golden * i) });
  }
  return directions;
}

std::shared_ptr<const EnvironmentMap> constantMap(int width, const Rgb& radiance)
{
  auto map = std::make_shared<EnvironmentMap>();
  map->width = width;
  map->height = width / 2;
  map->radiance.assign(std::size_t(map->width) * map->height, radiance);
  return map;
}

EnvironmentLight environmentLight(
  std::shared_ptr<const EnvironmentMap> map, EnvironmentEstimator estimator, int samples = 64)
{
  EnvironmentLight light;
  light.map = std::move(map);
  light.estimator = estimator;
  light.sampling.samples = samples;
  return light;
}

SurfacePoint surfacePoint(const glm::dvec3& position, const glm::dvec3& normal, std::uint64_t index = 0)
{
  SurfacePoint point;
  point.position = position;
  point.normal = glm::normalize(normal);
  point.toViewer = point.normal;
  point.index = index;
  return point;
}

const LobeModel noSpecular{};
const LobeModel blinnPhong30{ SpecularModel::BlinnPhong, 30 };
}

// docs/formulas.md sections 11.1 and 13.3: a constant environment L gives E = pi L at every normal.
TEST(EnvironmentEstimators, ConstantMapGivesPiLEverywhere)
{
  const Rgb radiance(0.5, 1.0, 2.0);
  const auto map = constantMap(256, radiance);
  const Rgb expected = pi * radiance;
  const auto normals = spreadDirections(50);

  auto largestRelativeError = [&](EnvironmentLight light)
  {
    const EnvironmentLightEstimator estimator(light, 0, noSpecular);
    double largest = 0;
    for (std::size_t i = 0; i < normals.size(); ++i)
    {
      const Rgb e = estimator.estimate(surfacePoint({ 0, 0, 0 }, normals[i], i)).irradiance;
      largest = std::max(largest, largestComponent((e - expected) / expected));
    }
    return largest;
  };
  // The sum over texels of max(0, n.w) Omega (the map downsampled to 128x64) and the
  // projection onto the basis are midpoint quadratures over the texels, exact only as the
  // texels shrink: measured 1.3e-4 and 3.0e-5 at 256x128.
  const double bruteForce = largestRelativeError(environmentLight(map, EnvironmentEstimator::BruteForce));
  const double sh = largestRelativeError(environmentLight(map, EnvironmentEstimator::SphericalHarmonics));
  std::cout << "constant map, largest relative error: brute force " << bruteForce << ", SH " << sh << "\n";
  EXPECT_LT(bruteForce, 1e-3);
  EXPECT_LT(sh, 1e-4);
  // Cosine-weighted directions: every sample is exactly pi L.
  EnvironmentLight cosine = environmentLight(map, EnvironmentEstimator::MonteCarlo);
  cosine.directions = EnvironmentDirections::Cosine;
  EXPECT_LT(largestRelativeError(cosine), 1e-14);
  // By luminance: a constant map is sampled uniformly over the sphere, which is not exact for
  // the cosine (relative std 1/sqrt(N) at best); with 4096 stratified samples it is within 1%.
  EXPECT_LT(largestRelativeError(environmentLight(map, EnvironmentEstimator::MonteCarlo, 4096)), 1e-2);
}

// docs/formulas.md section 12.3: every texel is a distant light of intensity L Omega. A map that is
// black but for one texel is that distant light.
TEST(EnvironmentEstimators, SingleBrightTexelIsADistantLight)
{
  auto map = std::make_shared<EnvironmentMap>(*constantMap(64, Rgb(0.0)));
  const int column = 40, row = 10;
  map->radiance[std::size_t(row) * map->width + column] = Rgb(1000, 500, 250);
  const glm::dvec3 towardTexel = texelCentreDirection(*map, column, row);
  const Rgb intensity = Rgb(1000, 500, 250) * texelSolidAngle(row, map->width, map->height);

  EnvironmentLight bruteForce = environmentLight(map, EnvironmentEstimator::BruteForce);
  bruteForce.bruteForceWidth = map->width; // every texel, no downsampling
  const EnvironmentLightEstimator exact(bruteForce, 0, blinnPhong30);
  const EnvironmentLightEstimator sampled(
    environmentLight(map, EnvironmentEstimator::MonteCarlo, 256), 0, blinnPhong30);
  // A texel spans at most this angle from its centre: 2 pi / 64 across the widest row.
  const double texelAngle = 2 * pi / map->width;
  int lit = 0;
  for (const glm::dvec3& n : spreadDirections(200))
  {
    SurfacePoint point = surfacePoint({ 0, 0, 0 }, n);
    point.toViewer = glm::normalize(glm::dvec3(0.3, 0.8, -0.2));
    const double cosIncidence = std::max(0.0, glm::dot(point.normal, towardTexel));
    lit += cosIncidence > 0;
    const DistributedTerms terms = exact.estimate(point);
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_NEAR(terms.irradiance[c], intensity[c] * cosIncidence, 1e-12 * intensity[c]);
      EXPECT_NEAR(terms.specular[c], intensity[c] * blinnPhong30(point.normal, towardTexel, point.toViewer),
        1e-12 * intensity[c]);
    }
    // By luminance every sample falls in that texel, at most texelAngle from its centre.
    const DistributedTerms estimate = sampled.estimate(point);
    EXPECT_NEAR(estimate.irradiance.x, intensity.x * cosIncidence, intensity.x * texelAngle);
  }
  EXPECT_GT(lit, 50); // the check covered lit and unlit normals
  EXPECT_LT(lit, 150);
}

// The map is turned about +y, anticlockwise seen from above: a map's +x turns to -z at 90 degrees.
TEST(EnvironmentEstimators, RotationTurnsTheMapAboutUp)
{
  auto map = std::make_shared<EnvironmentMap>(*constantMap(64, Rgb(0.0)));
  const int column = 48, row = 15; // u = 0.76, v = 0.48: near +x
  map->radiance[std::size_t(row) * map->width + column] = Rgb(1.0);
  EnvironmentLight light = environmentLight(map, EnvironmentEstimator::BruteForce);
  light.bruteForceWidth = map->width;
  light.rotationDegrees = 90;
  const EnvironmentLightEstimator estimator(light, 0, noSpecular);
  const glm::dvec3 inMap = texelCentreDirection(*map, column, row);
  const glm::dvec3 inWorld(inMap.z, inMap.y, -inMap.x); // +x -> -z, +z -> +x
  const double peak = texelSolidAngle(row, map->width, map->height);
  EXPECT_NEAR(estimator.estimate(surfacePoint({ 0, 0, 0 }, inWorld)).irradiance.x, peak, 1e-12 * peak);
  EXPECT_NEAR(estimator.estimate(surfacePoint({ 0, 0, 0 }, inMap)).irradiance.x,
    peak * std::max(0.0, glm::dot(inMap, inWorld)), 1e-12 * peak);
}

// docs/formulas.md section 12.5 gives 9.4% of the peak as the error of nine coefficients under a
// single small source at the horizon. The general bound behind it: the clamped cosine's
// Legendre series cut after l = 2 is 1/4 + t/2 + (15 t^2 - 5)/32 (coefficients 1/4, 1/2, 5/16),
// which differs from max(0, t) by at most 3/32 (at t = 0), so the error at any normal is at
// most 3/32 of the map's total sum of L Omega; for one source that is 9.4% of its peak. On the
// bundled maps, against the brute-force sum over the map downsampled to 256x128.
TEST(EnvironmentEstimators, SphericalHarmonicsAgainstBruteForceOnBundledMaps)
{
  for (const char* name : { "studio_small_03_1k.hdr", "venice_sunset_1k.hdr" })
  {
    const std::string file = shadelab::testing::sourcePath(std::string("data/envmaps/") + name);
    const auto map = std::make_shared<const EnvironmentMap>(readEnvironmentMap(file));
    double totalPower = 0; // sum of luminance x solid angle
    for (int row = 0; row < map->height; ++row)
    {
      for (int column = 0; column < map->width; ++column)
      {
        totalPower += luminance(map->texel(column, row)) * texelSolidAngle(row, map->width, map->height);
      }
    }
    EnvironmentLight reference = environmentLight(map, EnvironmentEstimator::BruteForce);
    reference.bruteForceWidth = 256;
    const EnvironmentLightEstimator bruteForce(reference, 0, noSpecular);
    const EnvironmentLightEstimator sh(environmentLight(map, EnvironmentEstimator::SphericalHarmonics), 0, noSpecular);
    double peak = 0, largestError = 0, errorSum = 0, irradianceSum = 0;
    for (const glm::dvec3& n : spreadDirections(2000))
    {
      const SurfacePoint point = surfacePoint({ 0, 0, 0 }, n);
      const double truth = luminance(bruteForce.estimate(point).irradiance);
      const double error = std::abs(luminance(sh.estimate(point).irradiance) - truth);
      peak = std::max(peak, truth);
      largestError = std::max(largestError, error);
      errorSum += error;
      irradianceSum += truth;
    }
    std::cout << name << ": SH irradiance (luminance) errs by at most " << largestError / peak
              << " of the peak irradiance (" << largestError / totalPower
              << " of the map's total L Omega; bound 3/32 = 0.094), on average " << errorSum / irradianceSum
              << " of the mean irradiance\n";
    EXPECT_LE(largestError, 3.0 / 32.0 * totalPower) << name;
  }
}

namespace
{
/// A unit square at height 1 above the origin, emitting downward (its vertices wind
/// anticlockwise seen from below).
AreaLight squareLight(AreaEstimator estimator, int samples = 64, bool stratified = true)
{
  AreaLight light;
  light.shape = PolygonEmitter{ { { -0.5, 1, -0.5 }, { 0.5, 1, -0.5 }, { 0.5, 1, 0.5 }, { -0.5, 1, 0.5 } } };
  light.color = Rgb(2.0);
  light.estimator = estimator;
  light.sampling = { samples, stratified };
  return light;
}

/// Receivers below the square: positions over the floor and normals that tilt up to nearly
/// horizontal, so that the horizon cuts the square for many of them.
std::vector<SurfacePoint> receiversUnderSquare(int count)
{
  std::vector<SurfacePoint> points;
  const auto normals = spreadDirections(2 * count);
  for (int i = 0; i < count; ++i)
  {
    glm::dvec3 n = normals[i]; // the upper half of the lattice: y > 0
    const glm::dvec3 position(std::sin(i * 1.3) * 1.5, 0.05 * (i % 5), std::cos(i * 0.7) * 1.5);
    points.push_back(surfacePoint(position, n, std::uint64_t(i)));
  }
  return points;
}

bool horizonCutsPolygon(const std::vector<glm::dvec3>& vertices, const SurfacePoint& point)
{
  int above = 0;
  for (const glm::dvec3& v : vertices)
  {
    above += glm::dot(v - point.position, point.normal) > 0;
  }
  return above > 0 && above < int(vertices.size());
}
}

TEST(AreaEstimators, PolygonExactAgainstMonteCarloWithinThreeStandardErrors)
{
  const AreaLight exactLight = squareLight(AreaEstimator::Exact);
  const AreaLightEstimator exact(exactLight, 0, noSpecular);
  const auto& vertices = std::get<PolygonEmitter>(exactLight.shape).vertices;
  for (const bool stratified : { false, true })
  {
    const AreaLightEstimator monteCarlo(squareLight(AreaEstimator::MonteCarlo, 1024, stratified), 0, noSpecular);
    int within = 0, withinOne = 0, straddling = 0, compared = 0;
    double squaredErrors = 0, squaredStandardErrors = 0;
    for (const SurfacePoint& point : receiversUnderSquare(400))
    {
      const double truth = exact.estimate(point).irradiance.x;
      const DistributedTerms estimate = monteCarlo.estimate(point);
      straddling += horizonCutsPolygon(vertices, point);
      if (estimate.irradianceStdError.x == 0)
      {
        // No sample fell above the horizon: at most a sliver of the square is visible.
        EXPECT_EQ(estimate.irradiance.x, 0);
        EXPECT_LT(truth, 1e-5);
        continue;
      }
      ++compared;
      within += std::abs(estimate.irradiance.x - truth) <= 3 * estimate.irradianceStdError.x;
      withinOne += std::abs(estimate.irradiance.x - truth) <= estimate.irradianceStdError.x;
      squaredErrors += (estimate.irradiance.x - truth) * (estimate.irradiance.x - truth);
      squaredStandardErrors += estimate.irradianceStdError.x * estimate.irradianceStdError.x;
    }
    std::cout << (stratified ? "stratified" : "independent") << ": " << within << " of " << compared
              << " estimates within 3 standard errors, " << withinOne << " within 1 (RMS error / RMS standard error "
              << std::sqrt(squaredErrors / squaredStandardErrors) << "); the horizon cuts the square for " << straddling
              << "\n";
    EXPECT_GT(straddling, 100);
    // Gaussian errors would put 99.7% within 3 standard errors.
    EXPECT_GE(within, 0.98 * compared);
    if (!stratified)
    {
      // and 68% within one: the standard error is neither too small nor too large.
      EXPECT_NEAR(double(withinOne) / compared, 0.68, 0.08);
    }
  }
}

// "samples": "auto" under a tolerance: each vertex's samples drawn in rounds until E's and S's
// standard errors meet their targets. Against the exact E: every vertex's standard error
// within the target unless it drew the maximum, 95% of the errors within the target's error,
// at least the light's own count drawn; S's standard error within its target too.
TEST(AreaEstimators, SamplesToATargetMeetItAtEveryVertexBelowTheMaximum)
{
  const AreaLight exactLight = squareLight(AreaEstimator::Exact);
  const AreaLightEstimator exact(exactLight, 0, noSpecular);
  const LobeModel phong{ SpecularModel::Phong, 20 };
  SampleTargets targets;
  targets.irradiance = SamplingTarget{ 0.02, 64, 1 << 16 };
  targets.specular = SamplingTarget{ 0.05, 64, 1 << 16 };
  const AreaLightEstimator sampled(squareLight(AreaEstimator::MonteCarlo), 0, phong, targets);
  int within = 0, compared = 0;
  for (const SurfacePoint& point : receiversUnderSquare(400))
  {
    const double truth = exact.estimate(point).irradiance.x;
    const DistributedTerms estimate = sampled.estimate(point);
    EXPECT_LE(estimate.irradianceStdError.x, targets.irradiance->standardError());
    EXPECT_LE(estimate.specularStdError.x, targets.specular->standardError());
    ++compared;
    within += std::abs(estimate.irradiance.x - truth) <= targets.irradiance->error;
  }
  std::cout << within << " of " << compared << " within the target's error\n";
  EXPECT_GE(within, 0.95 * compared);
  // Without targets, the light's fixed count: its first round is the light's own samples.
  const AreaLightEstimator fixed(squareLight(AreaEstimator::MonteCarlo), 0, phong);
  SampleTargets oneRound;
  oneRound.irradiance = SamplingTarget{ 1e9, 64, 64 };
  const AreaLightEstimator atMinimum(squareLight(AreaEstimator::MonteCarlo), 0, phong, oneRound);
  const SurfacePoint point = receiversUnderSquare(1).front();
  EXPECT_EQ(atMinimum.estimate(point).irradiance, fixed.estimate(point).irradiance);
}

// A one-sided emitter lights only the side its normal faces; a two-sided one both, alike.
TEST(AreaEstimators, OneSidedEmittersLightOnlyTheirFront)
{
  const SurfacePoint below = surfacePoint({ 0.1, 0, 0.2 }, { 0.2, 1, 0 });  // in front of the square
  const SurfacePoint above = surfacePoint({ 0.1, 2, 0.2 }, { 0.2, -1, 0 }); // its mirror image behind it
  AreaLight disk;
  disk.shape = DiskEmitter{ { 0, 1, 0 }, { 0, -1, 0 }, 0.4 };
  for (AreaLight light : { squareLight(AreaEstimator::Exact), disk })
  {
    for (const AreaEstimator estimator : { AreaEstimator::Exact, AreaEstimator::MonteCarlo, AreaEstimator::Point })
    {
      light.estimator = estimator;
      light.twoSided = false;
      const AreaLightEstimator oneSided(light, 0, blinnPhong30);
      const DistributedTerms front = oneSided.estimate(below);
      EXPECT_GT(front.irradiance.x, 0.1);
      EXPECT_EQ(oneSided.estimate(above).irradiance.x, 0.0);
      EXPECT_EQ(oneSided.estimate(above).specular.x, 0.0);
      light.twoSided = true;
      const AreaLightEstimator twoSided(light, 0, blinnPhong30);
      // Mirror images see the same, Monte Carlo too: the same vertex index draws the same
      // points on the emitter, which mirror onto themselves.
      EXPECT_NEAR(twoSided.estimate(above).irradiance.x, front.irradiance.x, 1e-12);
      EXPECT_EQ(twoSided.estimate(below).irradiance.x, front.irradiance.x);
    }
  }
}

// docs/formulas.md section 11.3 (Snyder 1996): the sphere's closed form, including the partly-below-horizon case,
// against Monte Carlo over the cone it subtends.
TEST(AreaEstimators, SphereClosedFormAgainstMonteCarlo)
{
  AreaLight light;
  light.shape = SphereEmitter{ { 0, 2, 0 }, 0.8 };
  light.estimator = AreaEstimator::Exact;
  const AreaLightEstimator exact(light, 0, noSpecular);
  light.estimator = AreaEstimator::MonteCarlo;
  light.sampling = { 1024, false };
  const AreaLightEstimator monteCarlo(light, 0, noSpecular);
  int within = 0, compared = 0, partly = 0;
  const auto normals = spreadDirections(300);
  for (std::size_t i = 0; i < normals.size(); ++i)
  {
    const SurfacePoint point = surfacePoint({ 0.3 * std::sin(double(i)), 0, 0 }, normals[i], i);
    const glm::dvec3 toCentre = glm::normalize(glm::dvec3(0, 2, 0) - point.position);
    const double sinHalfAngle = 0.8 / glm::length(glm::dvec3(0, 2, 0) - point.position);
    partly += std::abs(glm::dot(toCentre, point.normal)) < sinHalfAngle;
    const DistributedTerms estimate = monteCarlo.estimate(point);
    const double truth = exact.estimate(point).irradiance.x;
    if (estimate.irradianceStdError.x == 0)
    {
      EXPECT_EQ(estimate.irradiance.x, 0); // no sample above the horizon: a sliver at most
      EXPECT_LT(truth, 1e-5);
      continue;
    }
    ++compared;
    within += std::abs(estimate.irradiance.x - truth) <= 3 * estimate.irradianceStdError.x;
  }
  std::cout << within << " of " << compared << " within 3 standard errors; " << partly
            << " with the sphere partly below the horizon\n";
  EXPECT_GT(partly, 50);
  EXPECT_GE(within, 0.98 * compared);
}

// docs/formulas.md section 11.5, the "five-times rule": beyond five times its largest dimension, a
// source may be taken as a point. For a sphere wholly above the horizon the point is exact
// (pi L cos(beta) (r/d)^2 is I cos / d^2 with I = pi r^2 L); for a disk on its axis the
// relative error is (r/h)^2, 1% at five diameters.
TEST(AreaEstimators, PointApproximationBeyondFiveTimesTheSize)
{
  AreaLight sphere;
  sphere.shape = SphereEmitter{ { 0, 5, 0 }, 0.5 };
  AreaLight sphereAsPoint = sphere;
  sphereAsPoint.estimator = AreaEstimator::Point;
  const SurfacePoint tilted = surfacePoint({ 0, 0, 0 }, { 0.4, 1, 0.2 });
  const double sphereExact = AreaLightEstimator(sphere, 0, noSpecular).estimate(tilted).irradiance.x;
  EXPECT_NEAR(
    AreaLightEstimator(sphereAsPoint, 0, noSpecular).estimate(tilted).irradiance.x, sphereExact, 1e-12 * sphereExact);

  // Near the horizon the point lights all or nothing where the sphere is partly seen: over
  // every normal, the largest error relative to the sphere's peak pi L (r/d)^2: measured 0.043,
  // 0.021 and 0.0042 at 5, 10 and 50 radii, about 0.21 r/d.
  for (const double radii : { 5.0, 10.0, 50.0 })
  {
    AreaLight far = sphere;
    far.shape = SphereEmitter{ { 0, radii * 0.5, 0 }, 0.5 };
    AreaLight farAsPoint = far;
    farAsPoint.estimator = AreaEstimator::Point;
    const AreaLightEstimator exact(far, 0, noSpecular), point(farAsPoint, 0, noSpecular);
    const double peak = pi / (radii * radii);
    double largest = 0;
    for (const glm::dvec3& n : spreadDirections(20000))
    {
      const SurfacePoint receiver = surfacePoint({ 0, 0, 0 }, n);
      largest =
        std::max(largest, std::abs(point.estimate(receiver).irradiance.x - exact.estimate(receiver).irradiance.x));
    }
    std::cout << "sphere at " << radii << " radii: the point errs by at most " << largest / peak << " of the peak\n";
    EXPECT_LE(largest / peak, 0.25 / radii) << radii;
  }

  const double radius = 0.5;
  double previousError = 1;
  for (const double diameters : { 1.0, 2.0, 5.0, 10.0, 20.0 })
  {
    const double h = diameters * 2 * radius;
    AreaLight disk;
    disk.shape = DiskEmitter{ { 0, h, 0 }, { 0, -1, 0 }, radius };
    AreaLight diskAsPoint = disk;
    diskAsPoint.estimator = AreaEstimator::Point;
    const SurfacePoint below = surfacePoint({ 0, 0, 0 }, { 0, 1, 0 });
    const double exact = AreaLightEstimator(disk, 0, noSpecular).estimate(below).irradiance.x;
    const double point = AreaLightEstimator(diskAsPoint, 0, noSpecular).estimate(below).irradiance.x;
    EXPECT_NEAR(exact, pi * radius * radius / (radius * radius + h * h), 1e-12);
    const double error = (point - exact) / exact;
    EXPECT_NEAR(error, (radius / h) * (radius / h), 1e-9);
    EXPECT_LT(error, previousError);
    previousError = error;
    if (diameters == 5.0)
    {
      EXPECT_LE(error, 0.01);
    }
  }
}

namespace
{
/// Least-squares slope of log(error) against log(N).
double logLogSlope(const std::vector<double>& samples, const std::vector<double>& errors)
{
  const std::size_t n = samples.size();
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    const double x = std::log(samples[i]), y = std::log(errors[i]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}
}

// docs/formulas.md sections 13.1 and 13.2: Monte Carlo error falls as sigma / sqrt(N). Independent samples
// follow it; stratified samples do better on this smooth integrand.
TEST(AreaEstimators, MonteCarloErrorFallsAsOneOverRootN)
{
  const AreaLightEstimator exact(squareLight(AreaEstimator::Exact), 0, noSpecular);
  const auto receivers = receiversUnderSquare(200);
  const std::vector<double> counts = { 16, 64, 256, 1024, 4096 };
  for (const bool stratified : { false, true })
  {
    std::vector<double> rmsErrors;
    for (const double count : counts)
    {
      const AreaLightEstimator monteCarlo(
        squareLight(AreaEstimator::MonteCarlo, int(count), stratified), 0, noSpecular);
      double sum = 0;
      for (const SurfacePoint& point : receivers)
      {
        const double error = monteCarlo.estimate(point).irradiance.x - exact.estimate(point).irradiance.x;
        sum += error * error;
      }
      rmsErrors.push_back(std::sqrt(sum / receivers.size()));
    }
    const double slope = logLogSlope(counts, rmsErrors);
    std::cout << (stratified ? "stratified" : "independent") << ": RMS error from " << rmsErrors.front()
              << " (N = 16) to " << rmsErrors.back() << " (N = 4096), slope " << slope << "\n";
    if (stratified)
    {
      EXPECT_LT(slope, -0.6);
    }
    else
    {
      EXPECT_NEAR(slope, -0.5, 0.08);
    }
  }
}

TEST(MonteCarloEstimate, StandardErrorsOfKnownSamples)
{
  MonteCarloEstimate independent(false), stratified(true);
  for (const double f : { 1.0, 3.0, 2.0, 4.0 })
  {
    independent.add(Rgb(f));
    stratified.add(Rgb(f));
  }
  EXPECT_DOUBLE_EQ(independent.mean().x, 2.5);
  // Sample variance 5/3, standard error sqrt(5/3 / 4).
  EXPECT_DOUBLE_EQ(independent.standardError().x, std::sqrt(5.0 / 12.0));
  // Pairs (1, 3) and (2, 4): (4 + 4) / 4^2.
  EXPECT_DOUBLE_EQ(stratified.standardError().x, std::sqrt(0.5));
  stratified.add(Rgb(7.0)); // odd: the two pairs' sum scaled by 5/4, over 5^2
  EXPECT_DOUBLE_EQ(stratified.standardError().x, std::sqrt(8.0 * 5.0 / 4.0) / 5.0);
}

TEST(SampleSequence, OnePointPerCellAndTheSameForTheSameVertex)
{
  const Sampling sampling{ 12, true }; // a 4 x 3 grid
  const SampleSequence sequence(3, 77, sampling);
  std::vector<int> cells(12, 0);
  for (int j = 0; j < 12; ++j)
  {
    const glm::dvec2 u = sequence.point(j);
    ASSERT_GE(u.x, 0);
    ASSERT_LT(u.x, 1);
    ASSERT_GE(u.y, 0);
    ASSERT_LT(u.y, 1);
    ++cells[int(u.y * 4) * 3 + int(u.x * 3)];
    EXPECT_EQ(u, SampleSequence(3, 77, sampling).point(j));
    EXPECT_NE(u, SampleSequence(3, 78, sampling).point(j));
    EXPECT_NE(u, SampleSequence(4, 77, sampling).point(j));
  }
  EXPECT_EQ(cells, std::vector<int>(12, 1));
}

// Drawing directions by the lobe (LobeSampling.h): its density integrates to 1 over the
// sphere, for both lobes, broad and sharp.
TEST(LobeSampling, DensityIntegratesToOne)
{
  const glm::dvec3 n = glm::normalize(glm::dvec3(0.2, 1, 0.1));
  const glm::dvec3 v = glm::normalize(glm::dvec3(-0.5, 0.6, 0.3));
  for (const SpecularModel model : { SpecularModel::Phong, SpecularModel::BlinnPhong })
  {
    for (const double eta : { 1.0, 30.0, 300.0 })
    {
      const LobeModel lobe{ model, eta };
      // The sphere in 2048 x 1024 cells of exact solid angle, each at its centre.
      double integral = 0;
      const int width = 2048, height = 1024;
      for (int row = 0; row < height; ++row)
      {
        const double solidAngle = texelSolidAngle(row, width, height);
        for (int column = 0; column < width; ++column)
        {
          const glm::dvec3 s = directionAt((column + 0.5) / width, (row + 0.5) / height);
          integral += lobeDensity(lobe, n, v, s) * solidAngle;
        }
      }
      EXPECT_NEAR(integral, 1.0, 2e-3) << (model == SpecularModel::Phong ? "Phong" : "Blinn-Phong") << " eta " << eta;
    }
  }
}

// lobeWithDensity shares Blinn-Phong's power between the lobe and its density: both must be
// the bits of the lobe and lobeDensity, on every side of the normal and the viewer (n.h and
// n.s of either sign), at eta 0 (pow(0, 0) = 1) and where s = -v leaves h undefined.
TEST(LobeSampling, LobeWithDensityIsTheLobeAndTheDensity)
{
  std::mt19937_64 random(21);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  auto direction = [&] { return glm::normalize(glm::dvec3(uniform(random), uniform(random), uniform(random))); };
  int compared = 0, bothPositive = 0;
  for (const SpecularModel model : { SpecularModel::Phong, SpecularModel::BlinnPhong })
  {
    for (const double eta : { 0.0, 1.0, 40.0, 1e6 })
    {
      const LobeModel lobe{ model, eta };
      for (int i = 0; i < 2000; ++i)
      {
        const glm::dvec3 n = direction(), v = direction();
        const glm::dvec3 s = i == 0 ? -v : direction();
        const LobeAtDirection both = lobeWithDensity(lobe, n, v, s);
        EXPECT_EQ(both.value, lobe(n, s, v)) << eta;
        EXPECT_EQ(both.density, lobeDensity(lobe, n, v, s)) << eta;
        bothPositive += both.value > 0 && both.density > 0 ? 1 : 0;
        ++compared;
      }
    }
  }
  EXPECT_EQ(compared, 16000);
  EXPECT_GT(bothPositive, 3000);
}

// A lobe's draw knows the lobe and its density at the direction it drew (u.x / cos for cos^eta):
// the values lobeWithDensity computes there, to rounding, for both lobes, from eta 0 to 1e6, on
// every side of the normal and the viewer (Blinn-Phong's v.h < 0, where the lobe is 0 but the
// density is not).
TEST(LobeSampling, ADrawKnowsTheLobeAndItsDensityWhereItDrew)
{
  std::mt19937_64 random(34);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0), unit(0.0, 1.0);
  auto direction = [&] { return glm::normalize(glm::dvec3(uniform(random), uniform(random), uniform(random))); };
  int compared = 0, bothPositive = 0, densityOnly = 0;
  for (const SpecularModel model : { SpecularModel::Phong, SpecularModel::BlinnPhong })
  {
    for (const double eta : { 0.0, 1.0, 40.0, 1e6 })
    {
      const LobeModel lobe{ model, eta };
      for (int i = 0; i < 2000; ++i)
      {
        const glm::dvec3 n = direction(), v = direction();
        const LobeSample drawn = LobeDirections(lobe, n, v)({ unit(random), unit(random) });
        EXPECT_NEAR(glm::length(drawn.direction), 1.0, 1e-14);
        const LobeAtDirection there = lobeWithDensity(lobe, n, v, drawn.direction);
        // The cosine lobeWithDensity finds again from the direction errs by a few ulps, which
        // the power raises eta-fold; Blinn-Phong's h, found again from s + v of length 2 |v.h|,
        // loses digits as |v.h| falls, and its 1 / |v.h| loses as many again.
        const double grazing =
          model == SpecularModel::Phong ? 1.0 : std::abs(glm::dot(v, glm::normalize(drawn.direction + v)));
        const double relative = (1 + eta) * 1e-13 / (grazing * grazing);
        EXPECT_NEAR(drawn.lobe.value, there.value, relative * there.value) << eta;
        EXPECT_NEAR(drawn.lobe.density, there.density, relative * there.density) << eta;
        bothPositive += drawn.lobe.value > 0 && drawn.lobe.density > 0 ? 1 : 0;
        densityOnly += drawn.lobe.value == 0 && drawn.lobe.density > 0 ? 1 : 0;
        ++compared;
      }
    }
  }
  EXPECT_EQ(compared, 16000);
  EXPECT_GT(bothPositive, 3000);
  EXPECT_GT(densityOnly, 1000);
}

// S by luminance and lobe together against the brute-force sum over every texel of a smooth
// map, for a sharp lobe (eta 300) that luminance sampling alone would mostly miss.
TEST(EnvironmentEstimators, SpecularByBothStrategiesAgainstBruteForce)
{
  auto map = std::make_shared<EnvironmentMap>();
  map->width = 256;
  map->height = 128;
  for (int row = 0; row < map->height; ++row)
  {
    for (int column = 0; column < map->width; ++column)
    {
      const glm::dvec3 w = texelCentreDirection(*map, column, row);
      map->radiance.push_back(Rgb(1 + 0.8 * w.y + 0.5 * w.x * w.z, 1 + 0.3 * w.x, 0.5 + 0.5 * w.z * w.z));
    }
  }
  EnvironmentLight reference = environmentLight(map, EnvironmentEstimator::BruteForce);
  reference.bruteForceWidth = map->width;
  const LobeModel sharp{ SpecularModel::BlinnPhong, 300 };
  const EnvironmentLightEstimator bruteForce(reference, 0, sharp);
  // Independent samples, whose standard error is calibrated (stratified ones over-report it).
  EnvironmentLight monteCarlo = environmentLight(map, EnvironmentEstimator::MonteCarlo, 256);
  monteCarlo.sampling.stratified = false;
  const EnvironmentLightEstimator sampled(monteCarlo, 0, sharp);
  int within = 0, withinOne = 0, compared = 0;
  const auto normals = spreadDirections(200);
  for (std::size_t i = 0; i < normals.size(); ++i)
  {
    SurfacePoint point = surfacePoint({ 0, 0, 0 }, normals[i], i);
    point.toViewer = glm::normalize(normals[i] + glm::dvec3(0.3, 0.2, -0.4));
    const double truth = bruteForce.estimate(point).specular.x;
    const DistributedTerms estimate = sampled.estimate(point);
    if (truth < 1e-3)
    {
      continue; // the viewer below the horizon
    }
    ++compared;
    within += std::abs(estimate.specular.x - truth) <= 3 * estimate.specularStdError.x;
    withinOne += std::abs(estimate.specular.x - truth) <= estimate.specularStdError.x;
  }
  std::cout << within << " of " << compared << " specular estimates within 3 standard errors, " << withinOne
            << " within 1\n";
  EXPECT_GT(compared, 150);
  EXPECT_GE(within, 0.97 * compared);
  EXPECT_NEAR(double(withinOne) / compared, 0.68, 0.1);
}
