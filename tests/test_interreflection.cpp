// Diffuse interreflection (interreflection/Interreflection.h) against the closed forms of
// docs/formulas.md section 23: inside a closed sphere every wall element sees the wall with
// the same form factor, so k bounces of a uniform radiosity add rho + ... + rho^k of it; a
// spherical bowl of fraction f of the sphere sees itself with the fraction f; a convex mesh
// sees nothing of itself.
#include "CoreTestMeshes.h"
#include "Interreflection.h"
#include "MethodChoice.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

namespace
{
using namespace shadelab;
using namespace shadelab::testing;

/// Every vertex's gather rays traced from the radiosity, `rays` each (in reverse vertex order
/// where asked: the order does not matter), and how many met a triangle's back.
struct Gathered
{
  std::unique_ptr<BounceGather> gather;
  long backHits = 0;
};

Gathered gatherAll(const Mesh& mesh, const OccluderMesh& occluders, int rays, const std::vector<Rgb>& radiosity,
  bool reverse = false, const std::vector<Rgb>& carried = {})
{
  Gathered gathered{ std::make_unique<BounceGather>(occluders, radiosity, Sampling{ rays, true }, carried) };
  std::vector<OccluderMesh::RayHit> hits(static_cast<std::size_t>(rays));
  for (std::size_t k = 0; k < mesh.points.size(); ++k)
  {
    const std::size_t i = reverse ? mesh.points.size() - 1 - k : k;
    gathered.backHits +=
      gatherHits(occluders, mesh.vertex(i), { rays, true }, PackedPoints<double>{ &mesh.normals[0].x }, hits.data());
    gathered.gather->addVertex(i, hits.data());
  }
  return gathered;
}

/// gatherAll on both sides of a two-sided surface: radiosity holds the N fronts' values, then
/// the N backs'; each vertex gathers about its normal with lit backs, then about the opposite.
Gathered gatherBothSides(const Mesh& mesh, const OccluderMesh& occluders, int rays, const std::vector<Rgb>& radiosity)
{
  Gathered gathered{ std::make_unique<BounceGather>(
    occluders, radiosity, Sampling{ rays, true }, std::vector<Rgb>(), ShadedSides::Both) };
  std::vector<OccluderMesh::RayHit> hits(static_cast<std::size_t>(rays));
  const std::size_t n = mesh.points.size();
  for (std::size_t point = 0; point < 2 * n; ++point)
  {
    RayVertex vertex = mesh.vertex(point % n);
    vertex.normal = point < n ? vertex.normal : -vertex.normal;
    gathered.backHits += gatherHits(
      occluders, vertex, { rays, true }, PackedPoints<double>{ &mesh.normals[0].x }, hits.data(), TriangleBacks::Lit);
    gathered.gather->addVertex(point, hits.data());
  }
  return gathered;
}

double sumOfPowers(double x, int from, int to)
{
  double sum = 0;
  for (int n = from; n <= to; ++n)
  {
    sum += std::pow(x, n);
  }
  return sum;
}

/// A gather's mean and standard error at one vertex, in one channel.
struct GatherEstimateForTest
{
  double mean = 0, standardError = 0;
};

/// A closed sphere of radius 2, normals inward, lit from its centre by a point light of
/// intensity 3: E0 = I / R^2 at every vertex, and the radiosity rho E0.
struct LitClosedSphere
{
  explicit LitClosedSphere(double rho)
    : radiosity(sphere.points.size(), Rgb(rho * direct))
  {
  }
  static Mesh inside()
  {
    Mesh sphere;
    addSphere(sphere, glm::dvec3(0.5, -1, 2), 2.0, 16, 32, true);
    return sphere;
  }
  Mesh sphere = inside();
  OccluderMesh occluders = sphere.occluders();
  double direct = 3.0 / (2.0 * 2.0);
  std::vector<Rgb> radiosity;
};

// A point light of intensity I at the centre of a closed sphere of radius R lights every wall
// vertex with E0 = I / R^2, a uniform radiosity rho E0 that every gather ray meets, whatever
// triangle it hits: k bounces add (I / R^2)(rho + ... + rho^k), to rounding, with no spread.
TEST(Interreflection, AClosedSphereLitFromItsCentreGainsRhoToTheKOfItsLightPerBounce)
{
  const double rho = 0.6;
  const LitClosedSphere lit(rho);
  const Mesh& sphere = lit.sphere;
  const OccluderMesh& occluders = lit.occluders;
  const double direct = lit.direct;
  const std::vector<Rgb>& radiosity = lit.radiosity;
  for (int bounces = 1; bounces <= 4; ++bounces)
  {
    const Gathered gathered = gatherAll(sphere, occluders, 32, radiosity);
    EXPECT_EQ(gathered.backHits, 0);
    const IndirectIrradiance indirect = gathered.gather->bounce({ Rgb(rho), nullptr }, bounces, true);
    const double expected = direct * sumOfPowers(rho, 1, bounces);
    ASSERT_EQ(indirect.bounces.size(), std::size_t(bounces));
    for (std::size_t i = 0; i < sphere.points.size(); ++i)
    {
      ASSERT_NEAR(indirect.irradiance[i].g, expected, 1e-12 * expected) << "vertex " << i << ", " << bounces;
      ASSERT_LT(indirect.standardError[i].g, 1e-12 * expected);
      ASSERT_NEAR(indirect.bounces.back()[i].g, direct * std::pow(rho, bounces), 1e-12 * expected);
    }
  }
}

// With a share for what the bounces past K may add, bounce() stops at the fewest K whose bound
// max(B_K) rho / (1 - rho) fits it: in the closed sphere B_K = rho^(K+1) E0 everywhere, so the
// bound is exactly what is left out, and K is known in closed form. The result is the fixed-K
// run's bits. An albedo of 1 has no such K and is refused; a fixed count still runs, unbounded.
TEST(Interreflection, BouncesStopAtTheFewestWhoseRestFitsTheShare)
{
  const double rho = 0.6;
  const LitClosedSphere lit(rho);
  auto traced = [&] { return gatherAll(lit.sphere, lit.occluders, 32, lit.radiosity); }; // bounce() runs once
  for (const double share : { 0.1, 1e-3, 1e-6 })
  {
    int expected = 1;
    while (std::pow(rho, expected + 1) * lit.direct * rho / (1 - rho) > share)
    {
      ++expected;
    }
    const IndirectIrradiance adaptive = traced().gather->bounce({ Rgb(rho), nullptr }, { 64, share }, false);
    const IndirectIrradiance fixed = traced().gather->bounce({ Rgb(rho), nullptr }, expected, false);
    EXPECT_EQ(adaptive.bounceCount, expected) << share;
    EXPECT_LE(adaptive.restBound, share);
    EXPECT_NEAR(adaptive.restBound, lit.direct * sumOfPowers(rho, expected + 2, 2000), 1e-12 * lit.direct) << share;
    EXPECT_EQ(adaptive.irradiance, fixed.irradiance) << share;
    EXPECT_EQ(fixed.restBound, adaptive.restBound);
  }
  EXPECT_EQ(traced().gather->bounce({ Rgb(rho), nullptr }, { 3, 1e-9 }, false).bounceCount,
    3); // at most `most`
  std::vector<double> albedo(3 * lit.sphere.points.size(), rho);
  albedo[7] = 1.0;
  try
  {
    traced().gather->bounce({ Rgb(rho), albedo.data() }, { 64, 1e-3 }, false);
    ADD_FAILURE() << "an albedo of 1 was given a bound";
  }
  catch (const std::invalid_argument& error)
  {
    EXPECT_STREQ(error.what(),
      "an albedo up to 1 reflects all the light it receives: no number of bounces bounds what the rest add");
  }
  const IndirectIrradiance unbounded = traced().gather->bounce({ Rgb(rho), albedo.data() }, 2, false);
  EXPECT_TRUE(std::isinf(unbounded.restBound));
}

/// The form factor from a point at height h, facing down, to an a x b rectangle in the plane
/// below whose corner is under it: (X / sqrt(1 + X^2)) atan(Y / sqrt(1 + X^2)) + (X <-> Y), over
/// 2 pi, X = a / h, Y = b / h (J. R. Howell, "A Catalog of Radiation Heat Transfer Configuration
/// Factors", differential area to a parallel rectangle).
double cornerFormFactor(double a, double b, double h)
{
  const double x = a / h, y = b / h, pi = 3.14159265358979323846;
  const double sx = std::sqrt(1 + x * x), sy = std::sqrt(1 + y * y);
  return (x / sx * std::atan(y / sx) + y / sy * std::atan(x / sy)) / (2 * pi);
}

/// What a point at (-0.5, 0, 0.25), facing down, gathers with `rays` rays from the square
/// [-1, 1]^2 below it in cells x cells quads, whose radiosity at each corner is radiosity(x).
GatherEstimateForTest gatherAbovePlate(int cells, int rays, double (*radiosity)(double x))
{
  Mesh scene;
  addPlane(scene, 1.0, cells);
  const PointId receiver = scene.addPoint({ -0.5, 0, 0.25 }, { 0, 0, -1 });
  scene.addTriangle(receiver, scene.addPoint({ -0.5 + 1e-3, 0, 0.25 }, { 0, 0, -1 }),
    scene.addPoint({ -0.5, 1e-3, 0.25 }, { 0, 0, -1 }));
  std::vector<Rgb> values;
  for (const glm::dvec3& p : scene.points)
  {
    values.emplace_back(p.z == 0 ? radiosity(p.x) : 0.0);
  }
  const OccluderMesh occluders = scene.occluders();
  BounceGather gather(occluders, values, Sampling{ rays, true });
  std::vector<OccluderMesh::RayHit> hits(static_cast<std::size_t>(rays));
  gatherHits(occluders, scene.vertex(std::size_t(receiver)), { rays, true },
    PackedPoints<double>{ &scene.normals[0].x }, hits.data());
  gather.addVertex(std::size_t(receiver), hits.data());
  const IndirectIrradiance indirect = gather.bounce({ Rgb(1.0), nullptr }, 1, false);
  return { indirect.irradiance[std::size_t(receiver)].r, indirect.standardError[std::size_t(receiver)].r };
}

// Where interpolation fails: a sharp shadow edge across large triangles. The plate below the
// point is lit (radiosity 1) for x < 0 and dark beyond. Finely meshed, the gather meets the
// step's closed form, the form factor of the lit half (4 corner rectangles of 0.5 x 1 at height
// 0.25). Meshed as two triangles, the corners' values (1 at x = -1, 0 at x = 1) interpolate to
// the ramp (1 - x) / 2, and the gather meets the ramp's value, which a fine mesh of the ramp
// gives: it errs by the interpolation's error, far beyond its standard error, which more rays
// do not remove (at 4096 rays: 0.677 +- 0.0015 against the step's 0.883, and 0.886 +- 0.0019
// finely meshed).
TEST(Interreflection, ASharpShadowEdgeAcrossLargeTrianglesIsInterpolatedAway)
{
  auto step = [](double x) { return x < 0 ? 1.0 : x == 0 ? 0.5 : 0.0; };
  auto ramp = [](double x) { return (1 - x) / 2; };
  const double exact = 4 * cornerFormFactor(0.5, 1.0, 0.25);
  const GatherEstimateForTest fine = gatherAbovePlate(128, 4096, step);
  EXPECT_NEAR(fine.mean, exact, 3 * fine.standardError + 1e-3 * exact);
  const GatherEstimateForTest coarse = gatherAbovePlate(1, 4096, step);
  const GatherEstimateForTest fineRamp = gatherAbovePlate(128, 4096, ramp);
  EXPECT_NEAR(coarse.mean, fineRamp.mean, 3 * (coarse.standardError + fineRamp.standardError));
  EXPECT_GT(exact - coarse.mean, 0.1);
  EXPECT_GT(exact - coarse.mean, 50 * coarse.standardError);
}

// Under a tolerance the gather's rays double from the first run's count while the error, taken
// to fall as 1 / sqrt(N), is above the share, up to the maximum.
TEST(Interreflection, GatherRaysDoubleUntilTheirErrorFitsTheShare)
{
  EXPECT_EQ(gatherRaysWithin(0.1, 64, 0.1, 1024), 64);
  EXPECT_EQ(gatherRaysWithin(0.1, 64, 0.071, 1024), 128); // 0.1 / sqrt(2) = 0.0707
  EXPECT_EQ(gatherRaysWithin(0.1, 64, 0.049, 1024), 512); // 0.05 at 256, 0.035 at 512
  EXPECT_EQ(gatherRaysWithin(1.0, 64, 1e-6, 1024), 1024); // at most the maximum
  EXPECT_EQ(gatherRaysWithin(1.0, 64, 1e-6, 32), 64);     // the first run's are kept
}

// The light off the centre: the direct radiosity varies as cos / d^2, but after one bounce
// the wall has gathered the whole flux 4 pi I, spread evenly: rho I / R^2 at every vertex,
// within three standard errors and the tessellation's error.
TEST(Interreflection, AClosedSphereLitOffCentreIsLitEvenlyByItsFirstBounce)
{
  Mesh sphere;
  const double radius = 1.0, intensity = 1.0, rho = 0.5;
  const glm::dvec3 light(0.3, 0.2, -0.4);
  addSphere(sphere, glm::dvec3(0.0), radius, 48, 96, true);
  const OccluderMesh occluders = sphere.occluders();
  // The radiosity peaks where the light is near the wall: at 64 rays a vertex's mean is still
  // skewed (2% of the vertices beyond three standard errors, 0.7% at 256, 0.4% at 1024).
  std::vector<Rgb> radiosity(sphere.points.size());
  for (std::size_t i = 0; i < sphere.points.size(); ++i)
  {
    const glm::dvec3 toLight = light - sphere.points[i];
    const double d = glm::length(toLight);
    radiosity[i] = Rgb(rho * intensity * glm::dot(sphere.normals[i], toLight / d) / (d * d));
  }
  const Gathered gathered = gatherAll(sphere, occluders, 256, radiosity);
  const IndirectIrradiance indirect = gathered.gather->bounce({ Rgb(rho), nullptr }, 1, false);
  const double expected = rho * intensity / (radius * radius);
  int within = 0;
  double mean = 0;
  for (std::size_t i = 0; i < sphere.points.size(); ++i)
  {
    within += std::abs(indirect.irradiance[i].r - expected) <= 3 * indirect.standardError[i].r + 0.01 * expected;
    mean += indirect.irradiance[i].r / double(sphere.points.size());
  }
  EXPECT_GE(within, 0.99 * double(sphere.points.size()));
  EXPECT_NEAR(mean, expected, 0.005 * expected);
}

// A spherical bowl, the zone below polar angle theta0 (a fraction f = (1 + cos theta0) / 2 of the
// sphere), under a constant sky: each point of its inside sees the sky with the cosine-weighted
// fraction 1 - f and itself with f (Goebel 1967), so a uniform direct radiosity B0 gains
// B0 (f rho + ... + (f rho)^k) / rho of irradiance in k bounces.
TEST(Interreflection, ABowlSeesItselfWithTheFractionOfTheSphereItCovers)
{
  Mesh bowl;
  const double theta0 = 1.2, rho = 0.8, sky = 1.0;
  const double f = (1 + std::cos(theta0)) / 2;
  addSphereZone(bowl, glm::dvec3(0.0), 1.0, 48, 96, theta0, true);
  const OccluderMesh occluders = bowl.occluders();
  const double direct = M_PI * sky * (1 - f);
  const std::vector<Rgb> radiosity(bowl.points.size(), Rgb(rho * direct));
  for (int bounces : { 1, 3 })
  {
    const Gathered gathered = gatherAll(bowl, occluders, 256, radiosity);
    EXPECT_EQ(gathered.backHits, 0);
    const IndirectIrradiance indirect = gathered.gather->bounce({ Rgb(rho), nullptr }, bounces, false);
    const double expected = direct * sumOfPowers(f * rho, 1, bounces); // E_n = B0 f^n rho^(n-1), B0 = rho direct
    int within = 0;
    double mean = 0;
    for (std::size_t i = 0; i < bowl.points.size(); ++i)
    {
      within += std::abs(indirect.irradiance[i].b - expected) <= 3 * indirect.standardError[i].b + 0.01 * expected;
      mean += indirect.irradiance[i].b / double(bowl.points.size());
    }
    EXPECT_GE(within, 0.99 * double(bowl.points.size())) << bounces;
    EXPECT_NEAR(mean, expected, 0.01 * expected) << bounces;
  }
}

// The white furnace: with rho = 1 the bowl's total irradiance, direct and every bounce, tends to
// that of the open sky, pi L, whatever its shape.
TEST(Interreflection, AWhiteBowlUnderAConstantSkyTendsToTheOpenSky)
{
  Mesh bowl;
  const double theta0 = 0.6, sky = 1.0;
  const double f = (1 + std::cos(theta0)) / 2;
  addSphereZone(bowl, glm::dvec3(0.0), 1.0, 32, 64, theta0, true);
  const OccluderMesh occluders = bowl.occluders();
  const double direct = M_PI * sky * (1 - f);
  const std::vector<Rgb> radiosity(bowl.points.size(), Rgb(direct));
  const Gathered gathered = gatherAll(bowl, occluders, 64, radiosity);
  const IndirectIrradiance indirect = gathered.gather->bounce({ Rgb(1.0), nullptr }, 60, false);
  double mean = 0;
  for (std::size_t i = 0; i < bowl.points.size(); ++i)
  {
    mean += (direct + indirect.irradiance[i].r) / double(bowl.points.size());
  }
  EXPECT_NEAR(mean, M_PI * sky, 0.02 * M_PI * sky);
  EXPECT_GT(f, 0.9); // a deep bowl: the direct light alone is under a tenth of the sky's
}

// Seen from outside, a convex mesh meets nothing of itself: no indirect light at all, and no
// ray meets a back.
TEST(Interreflection, AConvexMeshSeenFromOutsideGetsNoIndirectLight)
{
  Mesh sphere;
  addSphere(sphere, glm::dvec3(0.0), 1.0, 16, 32);
  const OccluderMesh occluders = sphere.occluders();
  const std::vector<Rgb> radiosity(sphere.points.size(), Rgb(1.0));
  for (int bounces : { 1, 3 })
  {
    const Gathered gathered = gatherAll(sphere, occluders, 32, radiosity);
    EXPECT_EQ(gathered.backHits, 0);
    const IndirectIrradiance indirect = gathered.gather->bounce({ Rgb(0.9), nullptr }, bounces, false);
    for (std::size_t i = 0; i < sphere.points.size(); ++i)
    {
      ASSERT_EQ(indirect.irradiance[i], Rgb(0.0));
      ASSERT_EQ(indirect.standardError[i], Rgb(0.0));
    }
  }
}

// A surface sends out no negative light: a direct term below 0 (an SH estimate's ringing)
// reflects nothing, channel by channel.
TEST(Interreflection, ANegativeDirectTermReflectsNothing)
{
  Mesh sphere;
  addSphere(sphere, glm::dvec3(0.0), 1.0, 12, 24, true);
  const OccluderMesh occluders = sphere.occluders();
  const std::vector<Rgb> radiosity(sphere.points.size(), Rgb(-0.5, 0.25, -1e-3));
  const Gathered gathered = gatherAll(sphere, occluders, 16, radiosity);
  const IndirectIrradiance indirect = gathered.gather->bounce({ Rgb(0.5), nullptr }, 2, false);
  for (std::size_t i = 0; i < sphere.points.size(); ++i)
  {
    ASSERT_EQ(indirect.irradiance[i].r, 0.0);
    ASSERT_NEAR(indirect.irradiance[i].g, 0.25 * (1 + 0.5), 1e-14);
    ASSERT_EQ(indirect.irradiance[i].b, 0.0);
  }
}

// A closed sphere with its normals pointing out, gathered from its inside surface's points:
// every ray leaves into the solid and meets the wall's back, which carries nothing.
TEST(Interreflection, RaysThatMeetATrianglesBackCarryNothingAndAreCounted)
{
  Mesh inside;
  addSphere(inside, glm::dvec3(0.0), 1.0, 16, 32);
  for (glm::dvec3& n : inside.normals)
  {
    n = -n; // gather inward, toward the surface whose normals face out
  }
  Mesh outward;
  addSphere(outward, glm::dvec3(0.0), 1.0, 16, 32);
  const OccluderMesh occluders = outward.occluders();
  long backHits = 0;
  std::vector<OccluderMesh::RayHit> hits(16);
  for (std::size_t i = 0; i < inside.points.size(); ++i)
  {
    backHits +=
      gatherHits(occluders, inside.vertex(i), { 16, true }, PackedPoints<double>{ &outward.normals[0].x }, hits.data());
    for (const OccluderMesh::RayHit& hit : hits)
    {
      ASSERT_EQ(hit.triangle, OccluderMesh::RayHit::noTriangle);
    }
  }
  EXPECT_GT(backHits, long(0.95 * 16 * double(inside.points.size())));
}

// A two-sided closed sphere whose normals point out, lit from inside: its backs face the light
// and gather what the same sphere with inward normals gathers on its fronts, bit for bit (the
// same rays, about the same directions, meeting the same triangles, read on their backs), over
// every bounce; its fronts, outside, see nothing of it. The radiosity is a light's off the
// centre, so that every hit's value differs.
TEST(Interreflection, BothSidesOfATwoSidedSurfaceGatherWhatTheirOwnSideSends)
{
  Mesh inward;
  addSphere(inward, glm::dvec3(0.0), 1.0, 24, 48, true);
  Mesh outward = inward; // the same triangles, their normals turned round
  for (glm::dvec3& n : outward.normals)
  {
    n = -n;
  }
  const std::size_t n = inward.points.size();
  const glm::dvec3 light(0.3, 0.2, -0.4);
  std::vector<Rgb> inside(n), bothSides(2 * n, Rgb(0.0));
  for (std::size_t i = 0; i < n; ++i)
  {
    const glm::dvec3 toLight = light - inward.points[i];
    inside[i] = Rgb(0.5 * glm::dot(inward.normals[i], toLight) / std::pow(glm::length(toLight), 3));
    bothSides[n + i] = inside[i];
  }
  const OccluderMesh occluders = inward.occluders();
  const Albedo albedo{ Rgb(0.5, 0.6, 0.7), nullptr };
  const Gathered oneSide = gatherAll(inward, occluders, 32, inside);
  const IndirectIrradiance expected = oneSide.gather->bounce(albedo, 3, true);
  const Gathered twoSides = gatherBothSides(outward, occluders, 32, bothSides);
  const IndirectIrradiance gathered = twoSides.gather->bounce(albedo, 3, true);
  EXPECT_EQ(oneSide.backHits, 0);
  EXPECT_EQ(twoSides.backHits, 32 * long(n) - oneSide.backHits); // every back ray met a back, and carried it
  ASSERT_EQ(gathered.irradiance.size(), 2 * n);
  EXPECT_EQ(gathered.restBound, expected.restBound);
  for (std::size_t i = 0; i < n; ++i)
  {
    ASSERT_EQ(gathered.irradiance[i], Rgb(0.0)) << i;
    ASSERT_EQ(gathered.irradiance[n + i], expected.irradiance[i]) << i;
    ASSERT_EQ(gathered.standardError[n + i], expected.standardError[i]) << i;
    for (int b = 0; b < 3; ++b)
    {
      ASSERT_EQ(gathered.bounces[std::size_t(b)][n + i], expected.bounces[std::size_t(b)][i]) << i;
    }
  }
  EXPECT_GT(expected.irradiance[0].b, 0.1); // something was gathered
}

// Lit from its centre, the two-sided sphere's backs gain the closed sphere's (I / R^2)(rho + ...
// + rho^k), its fronts nothing, and one side's light does not leak to the other: the outside
// lit alone leaves the inside dark.
TEST(Interreflection, ATwoSidedSphereLitInsideKeepsItsLightInside)
{
  Mesh sphere;
  addSphere(sphere, glm::dvec3(0.5, -1, 2), 2.0, 16, 32);
  const std::size_t n = sphere.points.size();
  const OccluderMesh occluders = sphere.occluders();
  const double rho = 0.6, direct = 3.0 / (2.0 * 2.0);
  std::vector<Rgb> lit(2 * n, Rgb(0.0));
  std::fill(lit.begin() + std::ptrdiff_t(n), lit.end(), Rgb(rho * direct));
  const IndirectIrradiance inside =
    gatherBothSides(sphere, occluders, 32, lit).gather->bounce({ Rgb(rho), nullptr }, 4, false);
  std::vector<Rgb> outsideLit(2 * n, Rgb(0.0));
  std::fill(outsideLit.begin(), outsideLit.begin() + std::ptrdiff_t(n), Rgb(1.0));
  const IndirectIrradiance outside =
    gatherBothSides(sphere, occluders, 32, outsideLit).gather->bounce({ Rgb(rho), nullptr }, 4, false);
  const double expected = direct * sumOfPowers(rho, 1, 4);
  for (std::size_t i = 0; i < n; ++i)
  {
    ASSERT_EQ(inside.irradiance[i], Rgb(0.0)) << i;
    ASSERT_NEAR(inside.irradiance[n + i].r, expected, 1e-12 * expected) << i;
    ASSERT_EQ(outside.irradiance[i], Rgb(0.0)) << i;
    ASSERT_EQ(outside.irradiance[n + i], Rgb(0.0)) << i;
  }
}

// Each vertex depends only on the previous sweep: split into ranges in any order, the results
// are the same bits. Per-channel albedo colours the bounces channel by channel.
TEST(Interreflection, TheSameBitsHoweverTheSweepsAreSplitAndChannelsApart)
{
  Mesh bowl;
  addSphereZone(bowl, glm::dvec3(0.0), 1.0, 24, 48, 1.0, true);
  const OccluderMesh occluders = bowl.occluders();
  std::vector<Rgb> radiosity(bowl.points.size()), albedo(bowl.points.size());
  for (std::size_t i = 0; i < bowl.points.size(); ++i)
  {
    radiosity[i] = Rgb(1.0 + bowl.points[i].x, 0.5, 0.0);
    albedo[i] = Rgb(0.9, 0.5 * (1 + bowl.points[i].y), 0.2);
  }
  const Albedo varying{ Rgb(0.0), &albedo[0].x };
  const IndirectIrradiance serial = gatherAll(bowl, occluders, 32, radiosity).gather->bounce(varying, 3, true);
  const RangeLoop backwardsInPieces = [](std::size_t count, const std::function<void(std::size_t, std::size_t)>& body)
  {
    for (std::size_t last = count; last > 0;)
    {
      const std::size_t first = last > 37 ? last - 37 : 0;
      body(first, last);
      last = first;
    }
  };
  const IndirectIrradiance split =
    gatherAll(bowl, occluders, 32, radiosity, true).gather->bounce(varying, 3, true, backwardsInPieces);
  EXPECT_EQ(split.irradiance, serial.irradiance);
  EXPECT_EQ(split.standardError, serial.standardError);
  EXPECT_EQ(split.bounces, serial.bounces);
  for (std::size_t i = 0; i < bowl.points.size(); ++i)
  {
    const Rgb sum = serial.bounces[0][i] + serial.bounces[1][i] + serial.bounces[2][i];
    ASSERT_NEAR(serial.irradiance[i].r, sum.r, 1e-12 * (1 + sum.r));
    ASSERT_NEAR(serial.irradiance[i].g, sum.g, 1e-12 * (1 + sum.g));
    ASSERT_EQ(serial.irradiance[i].b, 0.0); // no blue to reflect
  }
}

// The later bounces gather on a quarter of 32 rays or more, a checkerboard of the strata spread
// over the hemisphere (every fourth ray keeps alternate columns of strata, a biased part of
// it): the second bounce's mean over a bowl with a varying radiosity is the same, to 1%, from 256
// rays (64 kept) as from 16 (all kept); and the white furnace above holds with 64 rays.
TEST(Interreflection, TheLaterBouncesGatherOnAQuarterOfTheRaysSpreadOverTheHemisphere)
{
  EXPECT_EQ(quarterOfGatherRays({ 64, true }).size(), 16u);
  EXPECT_EQ(quarterOfGatherRays({ 64, false }).size(), 16u);
  EXPECT_EQ(quarterOfGatherRays({ 31, true }).size(), 31u);
  Mesh bowl;
  addSphereZone(bowl, glm::dvec3(0.0), 1.0, 32, 64, 1.0, true);
  const OccluderMesh occluders = bowl.occluders();
  std::vector<Rgb> radiosity(bowl.points.size());
  for (std::size_t i = 0; i < bowl.points.size(); ++i)
  {
    radiosity[i] = Rgb(1.0 + bowl.points[i].x * bowl.points[i].x);
  }
  // Two bounces at kd = 1: E_2 gathers E_1 on the kept rays; E_1 itself on all of them.
  const IndirectIrradiance fine =
    gatherAll(bowl, occluders, 256, radiosity).gather->bounce({ Rgb(1.0), nullptr }, 2, true);
  const IndirectIrradiance coarse =
    gatherAll(bowl, occluders, 16, radiosity).gather->bounce({ Rgb(1.0), nullptr }, 2, true);
  double meanFine = 0, meanCoarse = 0;
  const double n = double(bowl.points.size());
  for (std::size_t i = 0; i < bowl.points.size(); ++i)
  {
    meanFine += fine.bounces[1][i].r / n;
    meanCoarse += coarse.bounces[1][i].r / n;
  }
  EXPECT_NEAR(meanFine, meanCoarse, 0.01 * meanFine);
}

// Fields carried through the bounces (a transfer vector's coefficients) take the same sweeps as
// the light: a field equal to the radiosity gets the light's irradiance bit for bit, its
// negative the negative bit for bit (a coefficient is signed, and not clamped as a light is),
// however many bounces the light's bound chooses; and the light's own arrays are the bits of a
// gather that carries nothing.
TEST(Interreflection, CarriedFieldsTakeTheLightsBouncesAndKeepTheirSign)
{
  Mesh bowl;
  addSphereZone(bowl, glm::dvec3(0.0), 1.0, 24, 48, 1.0, true);
  const OccluderMesh occluders = bowl.occluders();
  std::vector<Rgb> radiosity(bowl.points.size()), albedo(bowl.points.size()), carried;
  for (std::size_t i = 0; i < bowl.points.size(); ++i)
  {
    radiosity[i] = Rgb(1.0 + bowl.points[i].x, 0.5, 2.0 * bowl.points[i].z * bowl.points[i].z);
    albedo[i] = Rgb(0.9, 0.5 * (1 + bowl.points[i].y), 0.2);
    carried.push_back(radiosity[i]);
    carried.push_back(-radiosity[i]);
  }
  const Albedo varying{ Rgb(0.0), &albedo[0].x };
  const BounceLimit limit(64, 1e-3);
  const IndirectIrradiance alone = gatherAll(bowl, occluders, 32, radiosity).gather->bounce(varying, limit, true);
  const IndirectIrradiance carrying =
    gatherAll(bowl, occluders, 32, radiosity, false, carried).gather->bounce(varying, limit, true);
  ASSERT_GT(alone.bounceCount, 3);
  EXPECT_EQ(carrying.bounceCount, alone.bounceCount);
  EXPECT_EQ(carrying.irradiance, alone.irradiance);
  EXPECT_EQ(carrying.standardError, alone.standardError);
  EXPECT_EQ(carrying.bounces, alone.bounces);
  EXPECT_TRUE(alone.transfer.empty());
  ASSERT_EQ(carrying.transfer.size(), 2 * bowl.points.size());
  for (std::size_t i = 0; i < bowl.points.size(); ++i)
  {
    ASSERT_EQ(carrying.transfer[2 * i], alone.irradiance[i]) << i;
    ASSERT_EQ(carrying.transfer[2 * i + 1], -alone.irradiance[i]) << i;
  }
  EXPECT_THROW(BounceGather(occluders, radiosity, Sampling{ 32, true }, std::vector<Rgb>(3)), std::invalid_argument);
}
}
