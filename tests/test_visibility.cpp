// Visibility (visibility/Visibility.h) on meshes whose shadows and occlusion have closed
// forms: a convex mesh never hides anything from itself, a sphere's shadow on a plane is the
// exact segment-sphere test away from its edge, the sphere's occlusion of the plane is its form
// factor 1 - r^2 h / d^3, and an open box's is the form factor of its opening (Lambert's polygon
// formula). Ray origins are scale-invariant: the same results wherever the mesh is and
// whatever its size.
#include "AreaLightEstimator.h"
#include "CoreTestMeshes.h"
#include "PolygonIrradiance.h"
#include "SampleWarps.h"
#include "Visibility.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>
#include <random>

namespace
{
using namespace shadelab;
using namespace shadelab::testing;

/// The unit cube [0, 1]^3 without its top face, its faces facing inward, each in cells x cells
/// quads. Every point is stored once, its normal the mean of its faces' normals; or, with
/// pointsPerFace, each face has points of its own with the face's normal (as a mesh with hard
/// edges is written), so the points on the box's edges have copies.
Mesh openBox(int cells, bool pointsPerFace = false)
{
  Mesh box;
  std::vector<std::pair<glm::dvec3, glm::dvec3>> corners; // id -> (position, summed normal)
  auto pointAt = [&](const glm::dvec3& p, const glm::dvec3& n) -> PointId
  {
    for (std::size_t i = 0; i < corners.size(); ++i)
    {
      if (glm::length(corners[i].first - p) < 1e-12 && (!pointsPerFace || glm::dot(corners[i].second, n) > 0))
      {
        corners[i].second += n;
        return static_cast<PointId>(i);
      }
    }
    corners.push_back({ p, n });
    return static_cast<PointId>(corners.size() - 1);
  };
  // Each face: an origin and two edges whose cross product is its inward normal.
  const std::vector<std::array<glm::dvec3, 3>> faces = {
    { glm::dvec3(0, 0, 0), glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0) }, // floor, normal +z
    { glm::dvec3(0, 0, 0), glm::dvec3(0, 0, 1), glm::dvec3(1, 0, 0) }, // y = 0, normal +y
    { glm::dvec3(0, 1, 0), glm::dvec3(1, 0, 0), glm::dvec3(0, 0, 1) }, // y = 1, normal -y
    { glm::dvec3(0, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(0, 0, 1) }, // x = 0, normal +x
    { glm::dvec3(1, 0, 0), glm::dvec3(0, 0, 1), glm::dvec3(0, 1, 0) }, // x = 1, normal -x
  };
  std::vector<std::array<PointId, 3>> triangles;
  for (const auto& face : faces)
  {
    const glm::dvec3 origin = face[0], u = face[1], v = face[2];
    const glm::dvec3 n = glm::cross(u, v);
    auto id = [&](int i, int j) { return pointAt(origin + (double(i) / cells) * u + (double(j) / cells) * v, n); };
    for (int i = 0; i < cells; ++i)
    {
      for (int j = 0; j < cells; ++j)
      {
        triangles.push_back({ id(i, j), id(i + 1, j), id(i + 1, j + 1) });
        triangles.push_back({ id(i, j), id(i + 1, j + 1), id(i, j + 1) });
      }
    }
  }
  for (const auto& [p, n] : corners)
  {
    box.addPoint(p, n);
  }
  for (const auto& t : triangles)
  {
    box.addTriangle(t[0], t[1], t[2]);
  }
  return box;
}

/// AO's exact value in the open box: the form factor of the opening z = 1, P / pi.
double openBoxOcclusion(const glm::dvec3& p, const glm::dvec3& n)
{
  const std::vector<glm::dvec3> opening = { { 0, 0, 1 }, { 1, 0, 1 }, { 1, 1, 1 }, { 0, 1, 1 } };
  return polygonProjectedSolidAngle(opening, p, n) / M_PI;
}

/// The visibility of one light from one vertex.
LightVisibility visibilityOf(const OccluderMesh& occluders, const RayVertex& vertex, const glm::dvec3& toLight,
  double distance, SelfShadowing selfShadowing = SelfShadowing::SmoothSurface)
{
  LightVisibility visibility;
  const LightDirection direction{ toLight, distance };
  lightVisibility(occluders, &vertex, &direction, 1, false, &visibility, selfShadowing);
  return visibility;
}

TEST(Visibility, AConvexMeshNeverHidesALightOrTheSkyFromItself)
{
  // A coarse sphere: its points on the sphere, so each radial normal is the normal of a plane
  // that touches the mesh at the point alone, and no ray that leaves above that plane can meet
  // another facet. Rays leave from the points themselves, so the shadow terminator of a
  // coarse mesh (a facet rising above the normal's plane) cannot occur here.
  Mesh sphere;
  addSphere(sphere, { 0.3, -0.2, 0.1 }, 0.7, 6, 8);
  const OccluderMesh occluders = sphere.occluders();
  OcclusionSettings settings;
  settings.sampling.samples = 256;
  settings.bentNormal = true;
  settings.skyViewFactor = true;
  for (std::size_t i = 0; i < sphere.points.size(); ++i)
  {
    const OcclusionEstimate ao = ambientOcclusion(occluders, sphere.vertex(i), settings);
    EXPECT_EQ(ao.occlusion, 1.0) << "point " << i;
    EXPECT_EQ(ao.standardError, 1.0 / 256) << "point " << i; // one ray's weight, the least it reports
    EXPECT_EQ(ao.skyViewFactor, 1.0) << "point " << i;
    for (double azimuth = 0; azimuth < 6.28; azimuth += 0.7)
    {
      for (double z : { -0.9, -0.3, 0.0, 0.4, 0.95 })
      {
        const glm::dvec3 s(std::sqrt(1 - z * z) * std::cos(azimuth), std::sqrt(1 - z * z) * std::sin(azimuth), z);
        const LightVisibility distant = visibilityOf(occluders, sphere.vertex(i), s, INFINITY);
        EXPECT_EQ(distant.visible, glm::dot(s, sphere.normals[i]) > 0) << "point " << i;
        EXPECT_FALSE(distant.blockedByOwnTriangle);
      }
    }
  }
}

/// The shortest distance from c to the segment from p to q.
double distanceToSegment(const glm::dvec3& c, const glm::dvec3& p, const glm::dvec3& q)
{
  const glm::dvec3 d = q - p;
  const double t = std::clamp(glm::dot(c - p, d) / glm::dot(d, d), 0.0, 1.0);
  return glm::length(p + t * d - c);
}

TEST(Visibility, ASpheresShadowOnAPlaneIsTheSegmentSphereTestAwayFromItsEdge)
{
  Mesh scene;
  addPlane(scene, 2.0, 80);
  const std::size_t planePoints = scene.points.size();
  const glm::dvec3 centre(0, 0, 1);
  const double radius = 0.5;
  const int rows = 48, columns = 96;
  addSphere(scene, centre, radius, rows, columns);
  const OccluderMesh occluders = scene.occluders();
  // Every facet of the tessellated sphere lies between this radius and the sphere's: its
  // corners are on the sphere, and it spans at most this angle seen from the centre.
  const double facetAngle = std::hypot(M_PI / rows, 2 * M_PI / columns);
  const double innerRadius = radius * std::cos(facetAngle / 2);
  for (const glm::dvec3& light : { glm::dvec3(0.3, 0.2, 3.0), glm::dvec3(-1.5, 0.5, 2.5) })
  {
    std::size_t shadowed = 0, undecided = 0;
    for (std::size_t i = 0; i < planePoints; ++i)
    {
      const glm::dvec3 toLight = light - scene.points[i];
      const LightVisibility v = visibilityOf(occluders, scene.vertex(i), glm::normalize(toLight), glm::length(toLight));
      const double miss = distanceToSegment(centre, scene.points[i], light);
      if (miss < innerRadius)
      {
        EXPECT_FALSE(v.visible) << "plane point " << i << " is in the shadow of the inscribed sphere";
        ++shadowed;
      }
      else if (miss > radius)
      {
        EXPECT_TRUE(v.visible) << "plane point " << i << " sees the light past the sphere";
      }
      else
      {
        ++undecided;
      }
      EXPECT_FALSE(v.blockedByOwnTriangle);
    }
    EXPECT_GT(shadowed, 100u);               // the test has a shadow to look at
    EXPECT_LT(undecided, planePoints / 100); // and the tessellation's band is thin
  }
}

TEST(Visibility, RaysInPacketsGiveWhatRaysOneByOneGive)
{
  // The filter traces the rays of rayVertexGroup neighbouring vertices to a light in packets.
  Mesh scene;
  addPlane(scene, 2.0, 40);
  addSphere(scene, { 0, 0, 1 }, 0.5, 24, 48);
  const OccluderMesh occluders = scene.occluders();
  const glm::dvec3 light(0.3, 0.2, 3.0);
  std::size_t hidden = 0;
  for (std::size_t first = 0; first < scene.points.size(); first += rayVertexGroup)
  {
    const int count = static_cast<int>(std::min<std::size_t>(rayVertexGroup, scene.points.size() - first));
    RayVertex vertices[rayVertexGroup];
    LightDirection directions[rayVertexGroup];
    LightVisibility together[rayVertexGroup];
    for (int k = 0; k < count; ++k)
    {
      vertices[k] = scene.vertex(first + k);
      const glm::dvec3 d = light - vertices[k].position;
      directions[k] = { glm::normalize(d), glm::length(d) };
    }
    lightVisibility(occluders, vertices, directions, count, true, together);
    for (int k = 0; k < count; ++k)
    {
      LightVisibility alone;
      lightVisibility(occluders, &vertices[k], &directions[k], 1, true, &alone);
      EXPECT_EQ(together[k].visible, alone.visible) << "point " << first + k;
      EXPECT_EQ(together[k].blockedByOwnTriangle, alone.blockedByOwnTriangle) << "point " << first + k;
      hidden += alone.visible ? 0 : 1;
    }
  }
  EXPECT_GT(hidden, 100u);
}

TEST(Visibility, EmbreeAnswersARayAlikeInAnyPacket)
{
  // The visibility step fills packets with the rays of several vertices, and which vertices
  // share a packet depends on how the mesh is split over processes: each ray must get the
  // same answer alone (rtcOccluded1), in its own vertex's packets and in packets of any size
  // with any other rays. Rays from every vertex of a sphere over a plane, up to the sky and to
  // points of a square light, many grazing the sphere or the plane.
  Mesh scene;
  addPlane(scene, 2.0, 40);
  addSphere(scene, { 0, 0, 1 }, 0.5, 24, 48);
  const OccluderMesh occluders = scene.occluders();
  std::vector<OccluderMesh::FrameRay> rays;
  for (std::size_t i = 0; i < scene.points.size(); ++i)
  {
    const RayVertex v = scene.vertex(i);
    const OccluderMesh::FrameRay start = occluders.inFrame({ v.position, v.normal, {}, 0.0, v.id });
    const SampleSequence samples(5, i, { 32, true });
    for (int j = 0; j < samples.count(); ++j)
    {
      const glm::dvec2 u = samples.point(j);
      rays.push_back({ start.origin, glm::vec3(cosineWeightedDirection(v.normal, u).direction),
        std::numeric_limits<float>::infinity() });
      const glm::dvec3 offset = glm::dvec3(u.x - 0.5, u.y - 0.5, 2.0) - v.position;
      rays.push_back({ start.origin, glm::vec3(glm::normalize(offset)), occluders.frameDistance(glm::length(offset)) });
    }
  }
  std::vector<bool> alone(rays.size()), inOrder(rays.size()), mixed(rays.size());
  for (std::size_t i = 0; i < rays.size(); ++i)
  {
    alone[i] = occluders.occluded(&rays[i], 1) != 0;
  }
  constexpr std::size_t packet = OccluderMesh::bundleSize;
  for (std::size_t first = 0; first < rays.size(); first += packet)
  {
    const int count = static_cast<int>(std::min(packet, rays.size() - first));
    const unsigned hidden = occluders.occluded(&rays[first], count);
    for (int j = 0; j < count; ++j)
    {
      inOrder[first + j] = ((hidden >> j) & 1u) != 0;
    }
  }
  // Shuffled within windows of 4096 rays (so packets hold rays of nearby vertices, as they do
  // in the filter), in packets of 2 to 16.
  std::vector<std::size_t> order(rays.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::mt19937_64 random(26);
  for (std::size_t first = 0; first < order.size(); first += 4096)
  {
    std::shuffle(order.begin() + first, order.begin() + std::min(order.size(), first + 4096), random);
  }
  for (std::size_t first = 0; first < order.size();)
  {
    const int count = static_cast<int>(std::min<std::size_t>(2 + random() % 15, order.size() - first));
    OccluderMesh::FrameRay bundle[packet];
    for (int j = 0; j < count; ++j)
    {
      bundle[j] = rays[order[first + j]];
    }
    const unsigned hidden = occluders.occluded(bundle, count);
    for (int j = 0; j < count; ++j)
    {
      mixed[order[first + j]] = ((hidden >> j) & 1u) != 0;
    }
    first += static_cast<std::size_t>(count);
  }
  EXPECT_EQ(inOrder, alone);
  EXPECT_EQ(mixed, alone);
  const auto hidden = static_cast<std::size_t>(std::count(alone.begin(), alone.end(), true));
  EXPECT_GT(hidden, rays.size() / 10) << "of " << rays.size();
  EXPECT_LT(hidden, rays.size() * 9 / 10) << "of " << rays.size();
}

TEST(Visibility, TracingThePointsTogetherSetsTheBitsEachGetsAlone)
{
  // HiddenSampleTracer fills packets with the rays of several points; a point whose horizon
  // hides the whole light casts none.
  Mesh scene;
  addPlane(scene, 2.0, 20);
  addSphere(scene, { 0, 0, 1 }, 0.5, 12, 24);
  const OccluderMesh occluders = scene.occluders();
  AreaLight softbox;
  softbox.shape = PolygonEmitter{ { { -0.5, -0.5, 2.0 }, { -0.5, 0.5, 2.0 }, { 0.5, 0.5, 2.0 }, { 0.5, -0.5, 2.0 } } };
  softbox.sampling = { 80, true }; // two words of bits per point
  const AreaLightEstimator light(softbox, 0, LobeModel{});
  const int words = hiddenSampleWords(light.shadowRayCount());
  std::vector<std::uint64_t> together(scene.points.size() * words), alone(together.size());
  const std::vector<glm::dvec3>& corners = std::get<PolygonEmitter>(softbox.shape).vertices;
  HiddenSampleTracer tracer(occluders);
  std::size_t silent = 0;
  for (std::size_t i = 0; i < scene.points.size(); ++i)
  {
    const SurfacePoint point{ scene.points[i], scene.normals[i], { 0, 0, 1 }, i };
    const int cast = tracer.add(light, point, static_cast<PointId>(i), &together[i * words]);
    hiddenSamples(occluders, light, point, static_cast<PointId>(i), &alone[i * words]);
    silent += cast == 0 ? 1 : 0;
    // The highest corner of the light above the point's plane: none above, no ray; one well
    // above, some of the 80 samples are.
    double highest = -std::numeric_limits<double>::infinity();
    for (const glm::dvec3& corner : corners)
    {
      highest = std::max(highest, glm::dot(point.normal, corner - point.position));
    }
    if (highest <= 0)
    {
      EXPECT_EQ(cast, 0) << "point " << i;
    }
    if (highest > 0.3)
    {
      EXPECT_GT(cast, 0) << "point " << i;
    }
  }
  tracer.flush();
  EXPECT_EQ(together, alone);
  EXPECT_GT(silent, 100u); // the sphere's lower half faces away from the light
  EXPECT_GT(std::count_if(alone.begin(), alone.end(), [](std::uint64_t w) { return w != 0; }), 100);
}

/// Standard errors are calibrated when about 68% of the estimates are within one of the
/// exact value and at least 99% within three. Returns the fractions.
struct Calibration
{
  std::size_t count = 0, withinOne = 0, withinThree = 0;
  void add(double estimate, double standardError, double exact, double bias)
  {
    ++count;
    const double error = std::max(0.0, std::abs(estimate - exact) - bias);
    withinOne += error <= standardError ? 1 : 0;
    withinThree += error <= 3 * standardError ? 1 : 0;
  }
  double one() const { return double(withinOne) / count; }
  double three() const { return double(withinThree) / count; }
};

/// A UV sphere of radius 0.5 with its centre at height 1 over a square plane of half-width
/// `half`: the plane's points' occlusion is the sphere's form factor 1 - r^2 h / d^3.
struct SphereOverPlane
{
  static constexpr int rows = 64;
  const glm::dvec3 centre{ 0, 0, 1 };
  const double radius = 0.5;
  Mesh scene;
  std::size_t planePoints = 0;

  SphereOverPlane(double half, int cells)
  {
    addPlane(scene, half, cells);
    planePoints = scene.points.size();
    addSphere(scene, centre, radius, rows, 2 * rows);
  }
  double exactAt(std::size_t i) const
  {
    const double d = glm::length(centre - scene.points[i]);
    return 1 - radius * radius * centre.z / (d * d * d);
  }
  /// The tessellated sphere is inside the sphere and contains the sphere of radius
  /// r cos(facet angle / 2): its form factor is less, by at most that ratio of squared radii.
  static double tessellationBias(double exact)
  {
    const double facetAngle = std::hypot(M_PI / rows, M_PI / rows);
    return (1 - exact) * (1 - std::pow(std::cos(facetAngle / 2), 2));
  }
};

TEST(Visibility, ASphereOccludesThePlaneBelowByItsFormFactor)
{
  const SphereOverPlane sphereOverPlane(1.0, 40);
  const Mesh& scene = sphereOverPlane.scene;
  const std::size_t planePoints = sphereOverPlane.planePoints;
  const OccluderMesh occluders = scene.occluders();
  // Standard errors are calibrated, for independent samples and for stratified ones (two to a
  // stratum), and stratified ones have smaller errors.
  for (const bool stratified : { false, true })
  {
    OcclusionSettings settings;
    settings.sampling = { 256, stratified };
    Calibration calibration;
    double largestError = 0;
    for (std::size_t i = 0; i < planePoints; ++i)
    {
      const double exact = sphereOverPlane.exactAt(i);
      const OcclusionEstimate ao = ambientOcclusion(occluders, scene.vertex(i), settings);
      calibration.add(ao.occlusion, ao.standardError, exact, SphereOverPlane::tessellationBias(exact));
      largestError = std::max(largestError, std::abs(ao.occlusion - exact));
    }
    // Measured: independent 69.0% and 99.5%, largest error 0.085; stratified 72.5% and 99.6%,
    // largest error 0.039. Without one ray's variance added to the pairs' (Visibility.cpp),
    // stratified gave 68.9% and 98.7%: its variance rests on the few cells the silhouette crosses.
    EXPECT_NEAR(calibration.one(), 0.68, 0.05);
    EXPECT_GE(calibration.three(), 0.99);
    EXPECT_LT(largestError, stratified ? 0.05 : 0.1);
  }
}

TEST(Visibility, AnOpenBoxIsOccludedExactlyButForItsOpening)
{
  // Every point inside sees the sky through the opening alone, so its AO is the opening's form
  // factor: at the floor, on the walls, and at the concave edges and corners, where a ray into
  // a wall must not escape through the triangles around the point. With a point per face too,
  // where the floor's copy of an edge point lies in the wall's plane.
  for (const bool pointsPerFace : { false, true })
  {
    const Mesh box = openBox(12, pointsPerFace);
    const OccluderMesh occluders = box.occluders();
    OcclusionSettings settings;
    settings.sampling.samples = 256;
    Calibration calibration;
    std::size_t creasePoints = 0;
    for (std::size_t i = 0; i < box.points.size(); ++i)
    {
      const glm::dvec3 p = box.points[i];
      if (p.z > 1 - 1e-9)
      {
        continue; // the rim: the opening is edge-on
      }
      const double exact = openBoxOcclusion(p, box.normals[i]);
      const OcclusionEstimate ao = ambientOcclusion(occluders, box.vertex(i), settings);
      calibration.add(ao.occlusion, ao.standardError, exact, 0.0);
      const int onFaces = (p.x < 1e-9) + (p.x > 1 - 1e-9) + (p.y < 1e-9) + (p.y > 1 - 1e-9) + (p.z < 1e-9);
      if (onFaces >= 2)
      {
        ++creasePoints;
        // A ray that escaped through a wall would err by many rays' weight. Six standard errors
        // leave room for the tail of a few pairs: with a point per face, 2 crease points of
        // 188 are beyond four (each within 1.2 of its standard error with 65,536 rays).
        EXPECT_NEAR(ao.occlusion, exact, 6 * ao.standardError)
          << "crease point " << i << (pointsPerFace ? ", a point per face" : "");
      }
    }
    EXPECT_GT(creasePoints, 40u);
    // Stratified (the default): 71.5% within one standard error and 99.4% within three; with a
    // point per face, 69.9% and 99.1%.
    EXPECT_NEAR(calibration.one(), 0.68, 0.05);
    EXPECT_GE(calibration.three(), 0.99);
  }
}

TEST(Visibility, StandardErrorsFallAsOneOverTheRootOfTheRays)
{
  const Mesh box = openBox(6);
  const OccluderMesh occluders = box.occluders();
  const RayVertex floorCentre{ { 0.5, 0.5, 0.0 }, { 0, 0, 1 }, 0 };
  const double exact = openBoxOcclusion(floorCentre.position, floorCentre.normal);
  // The RMS error over many vertices' own patterns (ids), at 16 and 1024 rays.
  auto rmsError = [&](int rays)
  {
    OcclusionSettings settings;
    settings.sampling.samples = rays;
    double squares = 0;
    for (PointId id = 0; id < 200; ++id)
    {
      const double error =
        ambientOcclusion(occluders, { floorCentre.position, floorCentre.normal, id }, settings).occlusion - exact;
      squares += error * error;
    }
    return std::sqrt(squares / 200);
  };
  // 64 times the rays: at least 8 times less error (stratification does better).
  EXPECT_LT(rmsError(1024), rmsError(16) / 8);
}

TEST(SequentialSampling, NoVertexStopsBeforeTheRuleOfThreeOrPastTheMaximum)
{
  const SamplingTarget target = SamplingTarget::forFraction(0.02, 4096);
  EXPECT_EQ(target.standardError(), 0.01);
  EXPECT_EQ(target.minimum, 160) << "3 / 0.02 = 150 rays, in whole rounds of 16";
  EXPECT_EQ(target.nextRound(0, 0), 160);
  EXPECT_EQ(target.nextRound(160, 0.0099), 0) << "met past the minimum";
  EXPECT_EQ(target.nextRound(160, 0.0101), 16) << "a little short: one round";
  EXPECT_EQ(target.nextRound(160, 0.02), 160) << "4 times the rays wanted, at most twice drawn";
  EXPECT_EQ(target.nextRound(4000, 0.05), 96) << "up to the maximum, not past it";
  EXPECT_EQ(target.nextRound(4096, 0.05), 0);
  EXPECT_EQ(SamplingTarget::forFraction(1e-4, 4096).minimum, 4096) << "the rule of three past the maximum";
  EXPECT_EQ(SamplingTarget::forFraction(0.5, 4096).minimum, 16) << "at least a round";
}

TEST(SequentialSampling, TheErrorMostVerticesStayWithinFollowsTheNormalsQuantiles)
{
  // Closed forms of the normal distribution: P(|Z| > 1.959964) = 5%, P(|Z| > 1.644854) = 10%.
  EXPECT_NEAR(estimatedErrorQuantile(std::vector<double>(1000, 0.01), 0.95), 0.01959964, 1e-8);
  std::vector<double> halfSampled(1000, 0.0);
  std::fill_n(halfSampled.begin(), 500, 0.02);
  EXPECT_NEAR(estimatedErrorQuantile(halfSampled, 0.95), 0.02 * 1.644854, 1e-8)
    << "half the vertices exact: 10% of the other half beyond";
  // Two groups: 10% of the vertices at s = 1, 90% at s = 0.001. Only the first reach past a few
  // thousandths: x solves 0.1 P(|Z| > x) = 0.05, P(|Z| > x) = 0.5, x = 0.674490.
  std::vector<double> twoGroups(1000, 0.001);
  std::fill_n(twoGroups.begin(), 100, 1.0);
  EXPECT_NEAR(estimatedErrorQuantile(twoGroups, 0.95), 0.674490, 1e-6);
  std::vector<double> fewSampled(1000, 0.0);
  std::fill_n(fewSampled.begin(), 50, 1.0);
  EXPECT_EQ(estimatedErrorQuantile(fewSampled, 0.95), 0.0) << "95% of the vertices exact";
  EXPECT_EQ(estimatedErrorQuantile({}, 0.95), 0.0);
}

TEST(Visibility, RaysToATargetMeetItWhereverTheyStopShortOfTheMaximum)
{
  // The sphere over the plane again, with its form factor as the truth: every vertex's standard
  // error within the target's, unless it drew the maximum; 95% of the errors within the
  // target's error, less the tessellation's bias; each vertex's rays in whole rounds between
  // the minimum and the maximum, as many as it needed: fewer where the sphere is far.
  const SphereOverPlane sphereOverPlane(1.5, 30);
  const Mesh& scene = sphereOverPlane.scene;
  const std::size_t planePoints = sphereOverPlane.planePoints;
  const OccluderMesh occluders = scene.occluders();
  OcclusionSettings settings;
  settings.target = SamplingTarget::forFraction(0.02, 4096);
  std::size_t within = 0;
  int fewest = settings.target->maximum, most = 0;
  for (std::size_t i = 0; i < planePoints; ++i)
  {
    const double exact = sphereOverPlane.exactAt(i);
    const OcclusionEstimate ao = ambientOcclusion(occluders, scene.vertex(i), settings);
    EXPECT_LE(ao.standardError, settings.target->standardError()) << "vertex " << i << ", " << ao.rays << " rays";
    EXPECT_GE(ao.rays, settings.target->minimum);
    within +=
      std::abs(ao.occlusion - exact) - SphereOverPlane::tessellationBias(exact) <= settings.target->error ? 1 : 0;
    fewest = std::min(fewest, ao.rays);
    most = std::max(most, ao.rays);
  }
  // Measured: 96.2% within (two standard errors are 95.4% of a normal's), 160 to 656 rays.
  EXPECT_GE(double(within) / planePoints, 0.95);
  EXPECT_EQ(fewest, settings.target->minimum);
  EXPECT_GT(most, 2 * fewest);

  // A maximum below what the target needs: the vertices under the sphere stop at it, short.
  settings.target = SamplingTarget::forFraction(0.02, 64);
  const OcclusionEstimate capped = ambientOcclusion(occluders, { { 0.3, 0, 0 }, { 0, 0, 1 }, 7 }, settings);
  EXPECT_EQ(capped.rays, 64);
  EXPECT_GT(capped.standardError, settings.target->standardError());

  // A fixed count is what it was: one round of the vertex's samples.
  OcclusionSettings fixed;
  fixed.sampling.samples = 160;
  OcclusionSettings oneRound;
  oneRound.target = SamplingTarget::forFraction(3.0 / 160, 160);
  const RayVertex vertex{ { 0.3, 0, 0 }, { 0, 0, 1 }, 7 };
  EXPECT_EQ(
    ambientOcclusion(occluders, vertex, oneRound).occlusion, ambientOcclusion(occluders, vertex, fixed).occlusion);
}

TEST(Visibility, ResultsAreTheSameWhereverTheMeshIsAndWhateverItsSize)
{
  // Rays are cast in the frame of the mesh's bounding sphere, and their origins move by units
  // in the last place of that frame: moving the mesh by 1e4 or 1e6 or scaling it by 1e-3 or
  // 1e3 changes its float32 coordinates there by at most a unit in the last place. Each ray
  // then meets the same triangles but for rays that graze an edge: at most 1 in 1000 vertices
  // may see one ray of 64 differently.
  const Mesh box = openBox(10);
  OcclusionSettings settings;
  settings.maxDistance = 0.8;
  std::vector<double> reference;
  {
    const OccluderMesh occluders = box.occluders();
    for (std::size_t i = 0; i < box.points.size(); ++i)
    {
      reference.push_back(ambientOcclusion(occluders, box.vertex(i), settings).occlusion);
    }
  }
  for (const auto& [offset, scale] : { std::pair{ 1e4, 1.0 }, std::pair{ 1e6, 1.0 }, std::pair{ 0.0, 1e-3 },
         std::pair{ 0.0, 1e3 }, std::pair{ 1e6, 1e3 } })
  {
    const Mesh moved = box.placed(glm::dvec3(offset, -offset, 0.5 * offset), scale);
    OcclusionSettings scaled = settings;
    scaled.maxDistance = settings.maxDistance * scale;
    const OccluderMesh occluders = moved.occluders();
    std::size_t differing = 0;
    for (std::size_t i = 0; i < moved.points.size(); ++i)
    {
      const double ao = ambientOcclusion(occluders, moved.vertex(i), scaled).occlusion;
      EXPECT_LE(std::abs(ao - reference[i]), 1.0 / 64 + 1e-12) << "offset " << offset << ", scale " << scale;
      differing += ao != reference[i] ? 1 : 0;
    }
    EXPECT_LE(differing, moved.points.size() / 1000) << "offset " << offset << ", scale " << scale;
  }
}

TEST(Visibility, MaxDistanceLeavesOutFartherOccluders)
{
  // From the open box's floor centre, the walls are at least 0.5 away: with a max distance
  // of 0.4 nothing is hit; with 10, the box's exact value.
  const Mesh box = openBox(8);
  const OccluderMesh occluders = box.occluders();
  const RayVertex floorCentre{ { 0.5, 0.5, 0.0 }, { 0, 0, 1 }, 7 };
  OcclusionSettings settings;
  settings.sampling.samples = 1024;
  settings.maxDistance = 0.4;
  EXPECT_EQ(ambientOcclusion(occluders, floorCentre, settings).occlusion, 1.0);
  settings.maxDistance = 10;
  const OcclusionEstimate far = ambientOcclusion(occluders, floorCentre, settings);
  EXPECT_NEAR(far.occlusion, openBoxOcclusion(floorCentre.position, floorCentre.normal), 4 * far.standardError);
}

TEST(Visibility, AVertexInsideAClosedMeshSeesNoSky)
{
  // A point inside a closed sphere, facing any way: every ray meets the sphere, so AO is 0,
  // and no light is visible.
  Mesh scene;
  addSphere(scene, { 0, 0, 0 }, 1.0, 16, 32);
  const OccluderMesh occluders = scene.occluders();
  const RayVertex inside{ { 0.1, -0.2, 0.3 }, glm::normalize(glm::dvec3(1, 1, 0)), 0 };
  OcclusionSettings settings;
  settings.skyViewFactor = true;
  const OcclusionEstimate ao = ambientOcclusion(occluders, inside, settings);
  EXPECT_EQ(ao.occlusion, 0.0);
  EXPECT_EQ(ao.standardError, 1.0 / 64); // one ray's weight, the least it reports
  EXPECT_EQ(ao.skyViewFactor, 0.0);
  EXPECT_FALSE(visibilityOf(occluders, inside, glm::normalize(glm::dvec3(1, 0, 0)), INFINITY).visible);
}

TEST(Visibility, ALightBehindAWallAtAConcaveCornerIsBlockedByTheCornersOwnTriangles)
{
  // At the box's floor corner (0, 0, 0), the mean normal points into the box; a light whose
  // direction it faces but which lies behind the wall x = 0 is hidden by that wall, whose
  // first triangles have the corner point itself as a corner: flagged as such. With the
  // smooth surface, the walls' triangles around the corner (55 degrees from its normal) are
  // passed over as its rounding, and the wall beyond them hides the light.
  const Mesh box = openBox(8);
  const OccluderMesh occluders = box.occluders();
  std::size_t corner = 0;
  while (glm::length(box.points[corner]) > 1e-12)
  {
    ++corner;
  }
  const glm::dvec3 behindWall = glm::normalize(glm::dvec3(-0.2, 1.0, 1.0));
  ASSERT_GT(glm::dot(behindWall, box.normals[corner]), 0.0);
  for (const SelfShadowing selfShadowing : { SelfShadowing::SmoothSurface, SelfShadowing::Facets })
  {
    const LightVisibility v = visibilityOf(occluders, box.vertex(corner), behindWall, INFINITY, selfShadowing);
    EXPECT_FALSE(v.visible);
    EXPECT_TRUE(v.blockedByOwnTriangle);
  }
  // Into the box, past the opposite rim: visible.
  const LightVisibility open =
    visibilityOf(occluders, box.vertex(corner), glm::normalize(glm::dvec3(0.3, 0.3, 1.0)), INFINITY);
  EXPECT_TRUE(open.visible);
}

TEST(Visibility, ACopyOfThePointAtAHardEdgeCountsAsTheVertexsOwn)
{
  // With a point per face, the floor's copy of the corner (0, 0, 0) has the floor's normal, +z.
  // A light behind the wall x = 0 is hidden by the wall's triangles, whose corner there is
  // another copy of the point (another id, the same coordinates): still the vertex's own.
  const Mesh box = openBox(4, true);
  const OccluderMesh occluders = box.occluders();
  std::size_t copies = 0, floorCorner = box.points.size();
  for (std::size_t i = 0; i < box.points.size(); ++i)
  {
    if (glm::length(box.points[i]) < 1e-12)
    {
      ++copies;
      floorCorner = box.normals[i].z > 0.5 ? i : floorCorner;
    }
  }
  ASSERT_EQ(copies, 3u); // the floor's and the two walls'
  ASSERT_LT(floorCorner, box.points.size());
  const LightVisibility v =
    visibilityOf(occluders, box.vertex(floorCorner), glm::normalize(glm::dvec3(-0.2, 1.0, 1.0)), INFINITY);
  EXPECT_FALSE(v.visible);
  EXPECT_TRUE(v.blockedByOwnTriangle);
  // A light hidden by the far wall x = 1, which does not reach the corner: not the vertex's own.
  const LightVisibility far =
    visibilityOf(occluders, box.vertex(floorCorner), glm::normalize(glm::dvec3(1.0, 0.2, 0.3)), INFINITY);
  EXPECT_FALSE(far.visible);
  EXPECT_FALSE(far.blockedByOwnTriangle);
  // Lights seen through the opening are visible: the floor's copy lies in both walls' planes,
  // and its rays leave off the faces of all three copies (without that, every light was hidden).
  for (const glm::dvec3 toLight : { glm::dvec3(0.1, 0.1, 1.0), glm::dvec3(0.5, 0.5, 1.0), glm::dvec3(0.6, 0.2, 1.0) })
  {
    EXPECT_TRUE(visibilityOf(occluders, box.vertex(floorCorner), glm::normalize(toLight), INFINITY).visible)
      << toLight.x << " " << toLight.y << " " << toLight.z;
  }
}

/// A flat square grid at z = 0 (cells x cells of side 1 / cells about the origin, normals +z)
/// whose centre point is pushed down by depth: a dimple one ring wide, whose area-weighted
/// normal is still +z, the smallest bump of a scanned surface.
Mesh dimple(int cells, double depth)
{
  Mesh grid;
  addPlane(grid, 0.5, cells);
  const std::size_t centre = std::size_t(cells / 2) * std::size_t(cells + 1) + std::size_t(cells / 2);
  grid.points[centre].z = -depth;
  return grid;
}

TEST(Visibility, TheSmoothSurfacesOwnFacetsDoNotHideALightItsNormalFaces)
{
  // The dimple's walls rise at atan(depth / cell) = 21.8 degrees around its centre; a light 10
  // degrees above the horizon, which the centre's normal faces, is hidden there by the centre's
  // own triangles alone: the shadow terminator.
  const int cells = 8;
  const Mesh grid = dimple(cells, 0.05);
  const std::size_t centre = std::size_t(cells / 2) * std::size_t(cells + 1) + std::size_t(cells / 2);
  const OccluderMesh occluders = grid.occluders();
  const double elevation = 10 * M_PI / 180;
  for (double azimuth = 0; azimuth < 2 * M_PI; azimuth += M_PI / 8)
  {
    const glm::dvec3 toLight(
      std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth), std::sin(elevation));
    const LightVisibility facets =
      visibilityOf(occluders, grid.vertex(centre), toLight, INFINITY, SelfShadowing::Facets);
    EXPECT_FALSE(facets.visible) << azimuth;
    EXPECT_TRUE(facets.blockedByOwnTriangle) << azimuth;
    // The smooth surface: visible, and still flagged; and so for a point light as far as the
    // grid's edge (the ray, lifted above the dimple's rim, aims at the light again).
    const LightVisibility smooth = visibilityOf(occluders, grid.vertex(centre), toLight, INFINITY);
    EXPECT_TRUE(smooth.visible) << azimuth;
    EXPECT_TRUE(smooth.blockedByOwnTriangle) << azimuth;
    EXPECT_TRUE(visibilityOf(occluders, grid.vertex(centre), toLight, 0.5).visible) << azimuth;
  }

  // A wall across the light's path beyond the dimple still hides it.
  Mesh walled = grid;
  const PointId a = walled.addPoint({ 0.3, -1, -1 }, { -1, 0, 0 }), b = walled.addPoint({ 0.3, 1, -1 }, { -1, 0, 0 }),
                c = walled.addPoint({ 0.3, 1, 1 }, { -1, 0, 0 }), d = walled.addPoint({ 0.3, -1, 1 }, { -1, 0, 0 });
  walled.addTriangle(a, b, c);
  walled.addTriangle(a, c, d);
  const OccluderMesh walledOccluders = walled.occluders();
  const glm::dvec3 towardWall(std::cos(elevation), 0, std::sin(elevation));
  const LightVisibility behindWall = visibilityOf(walledOccluders, walled.vertex(centre), towardWall, INFINITY);
  EXPECT_FALSE(behindWall.visible);
  EXPECT_TRUE(behindWall.blockedByOwnTriangle);

  // Soft shadows alike: an area light's samples 10 degrees up, each hidden by the facets alone.
  std::vector<ShadowRay> rays;
  for (double azimuth = 0; azimuth < 2 * M_PI; azimuth += M_PI / 8)
  {
    rays.push_back(
      { { std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth), std::sin(elevation) },
        std::numeric_limits<double>::infinity(), true });
  }
  const SurfaceRay from{ grid.points[centre], grid.normals[centre], {}, 0.0, PointId(centre) };
  for (const SelfShadowing selfShadowing : { SelfShadowing::SmoothSurface, SelfShadowing::Facets })
  {
    std::uint64_t hidden = 0;
    HiddenSampleTracer tracer(occluders, selfShadowing);
    tracer.addRays(from, occluders.inFrame(from), rays.data(), int(rays.size()), &hidden);
    tracer.flush();
    EXPECT_EQ(hidden, selfShadowing == SelfShadowing::Facets ? (std::uint64_t(1) << rays.size()) - 1 : 0u);
  }
}

TEST(Visibility, ASpheresPointsOfEveryResolutionSeeEveryLightTheirNormalsFace)
{
  // Spheres of 12 to 400 segments around, under point lights near and far: no point whose
  // normal faces the light (n.s > 0.01) is darkened by the sphere itself.
  std::size_t facing = 0;
  for (int segments = 12; segments <= 400; ++segments)
  {
    Mesh sphere;
    addSphere(sphere, { 0.2, 0.1, -0.3 }, 1.5, segments / 2, segments);
    const OccluderMesh occluders = sphere.occluders();
    for (const glm::dvec3& light : { glm::dvec3(2.1, 0.3, 0.4), glm::dvec3(-40, 25, 10) })
    {
      std::vector<RayVertex> vertices;
      std::vector<LightDirection> directions;
      for (std::size_t i = 0; i < sphere.points.size(); ++i)
      {
        const glm::dvec3 toLight = light - sphere.points[i];
        if (glm::dot(glm::normalize(toLight), sphere.normals[i]) > 0.01)
        {
          vertices.push_back(sphere.vertex(i));
          directions.push_back({ glm::normalize(toLight), glm::length(toLight) });
        }
      }
      std::vector<LightVisibility> seen(vertices.size());
      for (std::size_t first = 0; first < vertices.size(); first += rayVertexGroup)
      {
        const int count = int(std::min<std::size_t>(rayVertexGroup, vertices.size() - first));
        lightVisibility(occluders, &vertices[first], &directions[first], count, false, &seen[first]);
      }
      for (std::size_t k = 0; k < seen.size(); ++k)
      {
        ASSERT_TRUE(seen[k].visible) << segments << " segments, point " << vertices[k].id;
      }
      facing += seen.size();
    }
  }
  std::cout << facing << " points facing a light, every one lit\n";
}

TEST(Visibility, ANormalConeHoldsTheAxisItWasGivenAndAHalfAngleAtLeastAsWide)
{
  // Stored in steps of 1/32767: the axis within a step of each coordinate, and the cosine
  // rounded down, never up, so that the cone holds every normal it was made from.
  for (int k = 0; k < 200; ++k)
  {
    const double z = 1 - (2 * k + 1) / 200.0, r = std::sqrt(1 - z * z), angle = 2.39996322972865332 * k;
    const glm::dvec3 axis(r * std::cos(angle), r * std::sin(angle), z);
    const double cosine = std::cos(0.0123 * k);
    const OccluderMesh::NormalCone cone = OccluderMesh::NormalCone::of(axis).withCosine(cosine);
    EXPECT_NEAR(glm::length(cone.axis() - axis), 0.0, 2.0 / 32767) << k;
    EXPECT_NEAR(glm::length(cone.axis()), 1.0, 1e-15) << k;
    EXPECT_LE(cone.cosine(), cosine) << k;
    EXPECT_GT(cone.cosine(), cosine - 1.0 / 32767) << k;
  }
}

TEST(Visibility, TheSearchForTheFirstHitEndingAtTheVertexsOwnTrianglesFindsWhatAWholeSearchFinds)
{
  // firstHitHasCorner with the vertex's id passes over the rays that move away from the planes
  // of all the vertex's triangles (and its copies'), and stops the others' search where those
  // triangles end; without the id it searches to the ray's end. The answers must agree on every
  // ray (with the screen always saying "away" they differed 1061 times, with a direction 0.05
  // below the planes taken as away, 9 times): from
  // every point of a coarse sphere over a plane (its terminator is its own triangles) and of
  // an open box written with a point per face (its corners have copies), in 64 directions
  // spread over the sphere, rays that the mesh blocks.
  Mesh spheres;
  addPlane(spheres, 2.0, 8);
  addSphere(spheres, { 0, 0, 0.6 }, 0.5, 5, 7);
  for (const Mesh& mesh : { spheres, openBox(3, true) })
  {
    const OccluderMesh occluders = mesh.occluders();
    std::size_t blocked = 0, own = 0;
    for (std::size_t i = 0; i < mesh.points.size(); ++i)
    {
      for (int k = 0; k < 64; ++k)
      {
        const double z = 1 - (2 * k + 1) / 64.0, r = std::sqrt(1 - z * z), angle = 2.39996322972865332 * k;
        const glm::dvec3 direction(r * std::cos(angle), r * std::sin(angle), z);
        const glm::dvec3 side = glm::dot(direction, mesh.normals[i]) >= 0 ? mesh.normals[i] : -mesh.normals[i];
        const OccluderMesh::FrameRay ray = occluders.inFrame({ mesh.points[i], side, direction, INFINITY, PointId(i) });
        if (occluders.occluded(&ray, 1) == 0)
        {
          continue;
        }
        ++blocked;
        const bool wholeSearch = occluders.firstHitHasCorner(ray, mesh.points[i]);
        EXPECT_EQ(occluders.firstHitHasCorner(ray, mesh.points[i], PointId(i)), wholeSearch)
          << "point " << i << ", direction " << k;
        own += wholeSearch ? 1 : 0;
      }
    }
    // Both answers occur often: the test has cases of each.
    EXPECT_GT(own, 200u);
    EXPECT_GT(blocked - own, 200u);
  }
}
}

// Once its BVH is released, a mesh still answers its corners and area vectors (what
// interreflection's sweeps need), and a ray traced refuses rather than reads as unblocked.
TEST(Visibility, AMeshWhoseTracingIsReleasedKeepsItsCornersAndRefusesRays)
{
  const Mesh box = openBox(2);
  OccluderMesh occluders = box.occluders();
  const std::array<std::uint32_t, 3> corners = occluders.corners(3);
  const glm::dvec3 area = occluders.areaVector(3);
  const OccluderMesh::FrameRay up = occluders.inFrame({ { 0.5, 0.5, 0.1 }, { 0, 0, 1 }, { 0, 0, 1 } });
  OccluderMesh::RayHit hit;
  occluders.firstHits(&up, 1, &hit);
  EXPECT_EQ(hit.triangle, OccluderMesh::RayHit::noTriangle); // the box's top is open

  occluders.releaseTracing();
  EXPECT_EQ(occluders.corners(3), corners);
  EXPECT_EQ(occluders.areaVector(3), area);
  EXPECT_THROW(occluders.firstHits(&up, 1, &hit), std::logic_error);
  EXPECT_THROW(occluders.occluded(&up, 1), std::logic_error);
}
