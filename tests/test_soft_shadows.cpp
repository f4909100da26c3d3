// Soft shadows of area lights (docs/formulas.md section 11.6) against a closed form: a square
// light parallel to the receiving plane, and between them a large opaque plate with a straight
// edge. From a receiver point the plate hides the part of the light beyond the edge's
// projection through the point, so the visible irradiance is Lambert's polygon formula on the
// light clipped by one line: a rectangle again.
#include "AreaLightEstimator.h"
#include "PolygonIrradiance.h"
#include "Visibility.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace
{
using namespace shadelab;

constexpr double lightHeight = 2, plateHeight = 1;
constexpr double lightHalf = 0.5; // the light is [-0.5, 0.5]^2 at z = 2, facing down
constexpr double radiance = 3;

/// The light's part x >= xFrom, wound as the light is (facing -z).
std::vector<glm::dvec3> lightFrom(double xFrom)
{
  const double x0 = std::max(-lightHalf, xFrom);
  return { { x0, lightHalf, lightHeight }, { lightHalf, lightHalf, lightHeight },
    { lightHalf, -lightHalf, lightHeight }, { x0, -lightHalf, lightHeight } };
}

AreaLight squareLight(AreaEstimator estimator, int samples, bool stratified)
{
  AreaLight light;
  light.shape = PolygonEmitter{ lightFrom(-lightHalf) };
  light.intensity = radiance;
  light.estimator = estimator;
  light.sampling = { samples, stratified };
  return light;
}

/// The plate z = 1, x < 0 (to x = -50), |y| < 50: two triangles.
struct Plate
{
  std::vector<glm::dvec3> points{ { -50, -50, plateHeight }, { 0, -50, plateHeight }, { 0, 50, plateHeight },
    { -50, 50, plateHeight } };
  std::vector<PointId> offsets{ 0, 3, 6 };
  std::vector<PointId> connectivity{ 0, 1, 2, 0, 2, 3 };
  OccluderMesh occluders() const
  {
    return OccluderMesh(
      PackedPoints<double>{ &points[0].x }, points.size(), PolygonList{ offsets.data(), connectivity.data(), 2 });
  }
};

/// The visible irradiance at (x, 0, 0) facing +z: a light point q is seen past the plate's edge
/// where the segment from the receiver crosses z = 1 at x >= 0, that is where q.x >= -x.
double visibleIrradiance(double x)
{
  if (-x >= lightHalf)
  {
    return 0;
  }
  return radiance * polygonProjectedSolidAngle(lightFrom(-x), { x, 0, 0 }, { 0, 0, 1 });
}

SurfacePoint receiver(double x, std::uint64_t index)
{
  return { { x, 0, 0 }, { 0, 0, 1 }, { 0, 0, 1 }, index };
}

/// The light's estimate at the receiver, with the plate's shadow.
DistributedTerms shadowed(const OccluderMesh& plate, const AreaLightEstimator& light, const SurfacePoint& point)
{
  std::vector<std::uint64_t> words(std::size_t(hiddenSampleWords(light.shadowRayCount())));
  hiddenSamples(plate, light, point, -1, words.data());
  return light.estimate(point, HiddenSamples{ words.data() });
}

/// Receivers across the penumbra (x from -0.5 to 0.5) and beyond it on both sides.
std::vector<double> receiverPositions(int count)
{
  std::vector<double> xs;
  for (int i = 0; i < count; ++i)
  {
    xs.push_back(-1 + 2.0 * (i + 0.5) / count);
  }
  return xs;
}

/// The share of receivers whose estimate is within three of its standard errors of the
/// closed form (and exact where the closed form is 0 or the vertex sees the whole light).
double shareWithinThreeErrors(AreaEstimator estimator, int samples)
{
  const Plate plate;
  const OccluderMesh occluders = plate.occluders();
  const AreaLightEstimator light(squareLight(estimator, samples, true), 7, LobeModel{});
  const std::vector<double> xs = receiverPositions(400);
  int within = 0;
  for (std::size_t i = 0; i < xs.size(); ++i)
  {
    const DistributedTerms terms = shadowed(occluders, light, receiver(xs[i], i));
    const double error = std::abs(terms.irradiance.x - visibleIrradiance(xs[i]));
    within += error <= 3 * terms.irradianceStdError.x + 1e-12 ? 1 : 0;
  }
  return double(within) / double(xs.size());
}

TEST(SoftShadows, MonteCarloMatchesTheClippedLightWithinThreeStandardErrors)
{
  EXPECT_GE(shareWithinThreeErrors(AreaEstimator::MonteCarlo, 256), 0.99);
}

TEST(SoftShadows, TheExactIrradianceTimesTheVisibleFractionDoesToo)
{
  EXPECT_GE(shareWithinThreeErrors(AreaEstimator::Exact, 256), 0.99);
}

TEST(SoftShadows, FullLightIsTheUnshadowedValueAndFullShadowIsZero)
{
  const Plate plate;
  const OccluderMesh occluders = plate.occluders();
  for (AreaEstimator estimator : { AreaEstimator::Exact, AreaEstimator::MonteCarlo, AreaEstimator::Point })
  {
    const AreaLightEstimator light(squareLight(estimator, 64, true), 7, LobeModel{ SpecularModel::BlinnPhong, 20 });
    // x = 0.75 sees the whole light past the edge; x = -0.75 sees none of it.
    const SurfacePoint lit = receiver(0.75, 1), dark = receiver(-0.75, 2);
    const DistributedTerms open = light.estimate(lit), seen = shadowed(occluders, light, lit);
    EXPECT_EQ(seen.irradiance, open.irradiance);
    EXPECT_EQ(seen.specular, open.specular);
    EXPECT_EQ(seen.visibility, 1.0);
    const DistributedTerms hidden = shadowed(occluders, light, dark);
    EXPECT_EQ(hidden.irradiance, Rgb(0.0));
    EXPECT_EQ(hidden.specular, Rgb(0.0));
    EXPECT_EQ(hidden.visibility, 0.0);
  }
  // The exact estimator's unshadowed E is the closed form itself.
  const AreaLightEstimator exact(squareLight(AreaEstimator::Exact, 64, true), 7, LobeModel{});
  EXPECT_NEAR(shadowed(occluders, exact, receiver(0.75, 1)).irradiance.x, visibleIrradiance(0.75), 1e-14);
}

/// The RMS error over the penumbra's receivers.
double penumbraRmsError(AreaEstimator estimator, int samples, bool stratified)
{
  const Plate plate;
  const OccluderMesh occluders = plate.occluders();
  const AreaLightEstimator light(squareLight(estimator, samples, stratified), 7, LobeModel{});
  double squares = 0;
  int count = 0;
  for (double x : receiverPositions(4000))
  {
    if (std::abs(x) < lightHalf)
    {
      const double error =
        shadowed(occluders, light, receiver(x, std::uint64_t(count))).irradiance.x - visibleIrradiance(x);
      squares += error * error;
      ++count;
    }
  }
  return std::sqrt(squares / count);
}

TEST(SoftShadows, TheErrorFallsAsOneOverTheSquareRootOfTheSamples)
{
  for (AreaEstimator estimator : { AreaEstimator::MonteCarlo, AreaEstimator::Exact })
  {
    // 16 times the samples: a quarter of the error for independent samples (measured 4.11 and
    // 4.10 over 2000 receivers), and about an eighth for stratified ones, a straight edge across
    // the strata erring as N^-3/4 (7.8 and 7.7).
    const double plain = penumbraRmsError(estimator, 64, false) / penumbraRmsError(estimator, 1024, false);
    EXPECT_GT(plain, 3.6);
    EXPECT_LT(plain, 4.6);
    const double stratified = penumbraRmsError(estimator, 64, true) / penumbraRmsError(estimator, 1024, true);
    EXPECT_GT(stratified, 6.5);
  }
}
}

namespace
{
/// Whether every term is a finite number, the visibility in [0, 1].
void expectFinite(const DistributedTerms& terms)
{
  for (const Rgb& value : { terms.irradiance, terms.specular, terms.irradianceStdError, terms.specularStdError })
  {
    EXPECT_TRUE(std::isfinite(value.x) && std::isfinite(value.y) && std::isfinite(value.z));
  }
  EXPECT_GE(terms.visibility, 0.0);
  EXPECT_LE(terms.visibility, 1.0);
  EXPECT_TRUE(std::isfinite(terms.visibilityStdError));
}

TEST(SoftShadowsFailurePoints, AVertexInTheLightsPlaneCastsNoRay)
{
  // Beside the light, in its plane: a one-sided emitter sends it nothing, so no ray is cast,
  // E is 0 and the visibility is 1 (nothing is hidden).
  const Plate plate;
  const OccluderMesh occluders = plate.occluders();
  const SurfacePoint beside{ { 1.5, 0, lightHeight }, { 0, 0, 1 }, { 0, 0, 1 }, 3 };
  for (AreaEstimator estimator : { AreaEstimator::Exact, AreaEstimator::MonteCarlo })
  {
    const AreaLightEstimator light(squareLight(estimator, 64, true), 7, LobeModel{ SpecularModel::Phong, 10 });
    std::vector<ShadowRay> rays(64);
    light.shadowRays(beside, rays.data());
    EXPECT_TRUE(std::none_of(rays.begin(), rays.end(), [](const ShadowRay& ray) { return ray.cast; }));
    const DistributedTerms terms = shadowed(occluders, light, beside);
    expectFinite(terms);
    EXPECT_EQ(terms.irradiance, Rgb(0.0));
    EXPECT_EQ(terms.visibility, 1.0);
    EXPECT_EQ(terms.visibilityStdError, 0.0);
  }
}

TEST(SoftShadowsFailurePoints, ALightCrossingTheSurfaceIsCutByTheHorizon)
{
  // A disk through the receiving plane, tilted: its lower half is below the horizon, where no
  // ray goes. Nothing else in the way: the unshadowed value bit for bit.
  const Plate plate;
  const OccluderMesh occluders = plate.occluders();
  AreaLight disk;
  disk.shape = DiskEmitter{ { 2.0, 0, 0 }, glm::normalize(glm::dvec3(-1, 0, -1)), 0.5 };
  for (AreaEstimator estimator : { AreaEstimator::Exact, AreaEstimator::MonteCarlo })
  {
    disk.estimator = estimator;
    const AreaLightEstimator light(disk, 7, LobeModel{});
    const SurfacePoint point = receiver(1.0, 4);
    const DistributedTerms terms = shadowed(occluders, light, point);
    expectFinite(terms);
    EXPECT_GT(terms.irradiance.x, 0.0);
    EXPECT_EQ(terms.irradiance, light.estimate(point).irradiance);
    EXPECT_EQ(terms.visibility, 1.0);
  }
}

TEST(SoftShadowsFailurePoints, GrazingOccluders)
{
  const Plate plate;
  const OccluderMesh occluders = plate.occluders();
  const AreaLightEstimator light(squareLight(AreaEstimator::Exact, 1024, true), 7, LobeModel{});
  // Right under the plate's edge, half the light is hidden: rays pass the edge at every angle.
  const DistributedTerms under = shadowed(occluders, light, receiver(0.0, 5));
  expectFinite(under);
  EXPECT_NEAR(under.irradiance.x, visibleIrradiance(0.0), 3 * under.irradianceStdError.x);
  EXPECT_NEAR(under.visibility, 0.5, 0.05);
  // Level with the plate, just beyond its edge, facing up: every ray climbs away from the
  // plate's plane, none is stopped by it.
  const SurfacePoint level{ { 0.25, 0, plateHeight }, { 0, 0, 1 }, { 0, 0, 1 }, 6 };
  const DistributedTerms grazing = shadowed(occluders, light, level);
  EXPECT_EQ(grazing.visibility, 1.0);
  EXPECT_EQ(grazing.irradiance, light.estimate(level).irradiance);
}
}
