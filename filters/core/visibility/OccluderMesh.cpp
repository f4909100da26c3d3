#include "OccluderMesh.h"

#include "RayOrigin.h"
#include "SampleSequence.h"

#include <embree3/rtcore.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>

namespace shadelab
{
namespace
{
/// A key equal for equal coordinates (-0 and +0 alike), from their bits.
std::uint64_t coordinateKey(const float* p)
{
  std::uint64_t key = 0x9e3779b97f4a7c15ull;
  for (int i = 0; i < 3; ++i)
  {
    const float zeroSigned = p[i] + 0.0f; // -0 + 0 is +0
    std::uint32_t bits;
    std::memcpy(&bits, &zeroSigned, sizeof bits);
    key = mix64(key ^ bits);
  }
  return key;
}

constexpr std::uint32_t noCopies = std::numeric_limits<std::uint32_t>::max();

/// Per point (x, y, z per point, in the unit frame), the group of the points with its
/// coordinates, or noCopies where it has none; empty when no point has a copy.
std::vector<std::uint32_t> copyGroupsOf(const std::vector<float>& xyz, std::size_t pointCount, std::uint32_t& groups)
{
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keys;
  keys.reserve(pointCount);
  for (std::size_t i = 0; i < pointCount; ++i)
  {
    if (std::isfinite(xyz[3 * i]))
    {
      keys.emplace_back(coordinateKey(&xyz[3 * i]), static_cast<std::uint32_t>(i));
    }
  }
  std::sort(keys.begin(), keys.end());
  std::vector<std::uint32_t> group; // filled once a copy is found
  groups = 0;
  auto same = [&](std::uint32_t a, std::uint32_t b) { return std::equal(&xyz[3 * a], &xyz[3 * a + 3], &xyz[3 * b]); };
  for (std::size_t k = 1; k < keys.size(); ++k)
  {
    const std::uint32_t previous = keys[k - 1].second, point = keys[k].second;
    if (keys[k].first == keys[k - 1].first && same(previous, point))
    {
      group.resize(pointCount, noCopies);
      if (group[previous] == noCopies)
      {
        group[previous] = groups++;
      }
      group[point] = group[previous];
    }
  }
  return group;
}

glm::dvec3 unitPoint(const std::vector<float>& xyz, std::uint32_t id)
{
  return { xyz[3 * std::size_t(id)], xyz[3 * std::size_t(id) + 1], xyz[3 * std::size_t(id) + 2] };
}

/// The area vector (twice the area, along the normal) of the triangle whose corners are
/// corners[0..2].
glm::dvec3 areaVectorOf(const std::vector<float>& xyz, const std::uint32_t* corners)
{
  const glm::dvec3 a = unitPoint(xyz, corners[0]);
  return glm::cross(unitPoint(xyz, corners[1]) - a, unitPoint(xyz, corners[2]) - a);
}

/// OccluderMesh::jointNormals_ for these points and triangles, given their copy groups.
std::vector<glm::vec3> jointNormalsOf(const std::vector<float>& xyz, const std::vector<std::uint32_t>& triangles,
  const std::vector<std::uint32_t>& group, std::uint32_t groups)
{
  if (groups == 0)
  {
    return {};
  }
  std::vector<glm::dvec3> sums(groups, glm::dvec3(0.0));
  for (std::size_t t = 0; t < triangles.size(); t += 3)
  {
    const glm::dvec3 area = areaVectorOf(xyz, &triangles[t]);
    for (std::size_t c = t; c < t + 3; ++c)
    {
      if (group[triangles[c]] != noCopies && std::isfinite(area.x + area.y + area.z))
      {
        sums[group[triangles[c]]] += area;
      }
    }
  }
  std::vector<glm::vec3> normals(group.size(), glm::vec3(0.0f));
  for (std::size_t i = 0; i < group.size(); ++i)
  {
    const double length = group[i] == noCopies ? 0.0 : glm::length(sums[group[i]]);
    normals[i] = length > 0 ? glm::vec3(sums[group[i]] / length) : glm::vec3(0.0f);
  }
  return normals;
}

/// OccluderMesh::ownReach_ for these points and triangles, given their copy groups.
std::vector<float> ownReachOf(const std::vector<float>& xyz, std::size_t pointCount,
  const std::vector<std::uint32_t>& triangles, const std::vector<std::uint32_t>& group, std::uint32_t groups)
{
  std::vector<float> reach(pointCount, 0.0f);
  auto reachAtLeast = [&](std::uint32_t point, float a, float b) { reach[point] = std::max({ reach[point], a, b }); };
  for (std::size_t t = 0; t < triangles.size(); t += 3)
  {
    const std::uint32_t a = triangles[t], b = triangles[t + 1], c = triangles[t + 2];
    // A NaN length (a point left out of the BVH) is passed over by std::max.
    const float ab = static_cast<float>(glm::length(unitPoint(xyz, b) - unitPoint(xyz, a)));
    const float bc = static_cast<float>(glm::length(unitPoint(xyz, c) - unitPoint(xyz, b)));
    const float ca = static_cast<float>(glm::length(unitPoint(xyz, a) - unitPoint(xyz, c)));
    reachAtLeast(a, ab, ca);
    reachAtLeast(b, ab, bc);
    reachAtLeast(c, bc, ca);
  }
  if (groups > 0)
  {
    std::vector<float> groupReach(groups, 0.0f);
    for (std::size_t i = 0; i < pointCount; ++i)
    {
      if (group[i] != noCopies)
      {
        groupReach[group[i]] = std::max(groupReach[group[i]], reach[i]);
      }
    }
    for (std::size_t i = 0; i < pointCount; ++i)
    {
      reach[i] = group[i] == noCopies ? reach[i] : groupReach[group[i]];
    }
  }
  return reach;
}

/// OccluderMesh::ownNormalCones_ for these points and triangles, given their copy groups: per
/// point, the sum of the unit normals of the triangles around it and its copies as its axis,
/// and the least cosine between that axis (as stored, NormalCone) and any of them. No cone where
/// a triangle's normal is too ill-conditioned for float to agree with it (an angle below 1e-3
/// radians), where the normals cancel, or where the cone is half a sphere or wider.
std::vector<OccluderMesh::NormalCone> ownNormalConesOf(const std::vector<float>& xyz, std::size_t pointCount,
  const std::vector<std::uint32_t>& triangles, const std::vector<std::uint32_t>& group, std::uint32_t groups)
{
  constexpr double noCone = -1;
  auto slotOf = [&](std::uint32_t point)
  { return group.empty() || group[point] == noCopies ? std::size_t(point) : pointCount + group[point]; };
  auto normalOf = [&](std::size_t t, bool& wellConditioned)
  {
    const glm::dvec3 a = unitPoint(xyz, triangles[t]), e1 = unitPoint(xyz, triangles[t + 1]) - a,
                     e2 = unitPoint(xyz, triangles[t + 2]) - a;
    const glm::dvec3 n = glm::cross(e1, e2);
    const double length = glm::length(n);
    wellConditioned = length > 1e-3 * glm::length(e1) * glm::length(e2) && std::isfinite(length);
    return wellConditioned ? n / length : glm::dvec3(0.0);
  };
  std::vector<glm::dvec3> axes(pointCount + groups, glm::dvec3(0.0));
  std::vector<double> least(pointCount + groups, 1.0);
  for (std::size_t t = 0; t < triangles.size(); t += 3)
  {
    bool wellConditioned = false;
    const glm::dvec3 n = normalOf(t, wellConditioned);
    for (std::size_t c = t; c < t + 3; ++c)
    {
      axes[slotOf(triangles[c])] += n;
      least[slotOf(triangles[c])] = wellConditioned ? least[slotOf(triangles[c])] : noCone;
    }
  }
  // The least cosines are measured from the axes as stored.
  std::vector<OccluderMesh::NormalCone> cones(pointCount + groups);
  for (std::size_t slot = 0; slot < axes.size(); ++slot)
  {
    const double length = glm::length(axes[slot]);
    cones[slot] = OccluderMesh::NormalCone::of(length > 1e-6 ? axes[slot] / length : glm::dvec3(0.0));
    axes[slot] = cones[slot].axis();
  }
  for (std::size_t t = 0; t < triangles.size(); t += 3)
  {
    bool wellConditioned = false;
    const glm::dvec3 n = normalOf(t, wellConditioned);
    for (std::size_t c = t; c < t + 3; ++c)
    {
      const std::size_t slot = slotOf(triangles[c]);
      least[slot] = std::min(least[slot], glm::dot(axes[slot], n));
    }
  }
  std::vector<OccluderMesh::NormalCone> pointCones(pointCount);
  for (std::size_t i = 0; i < pointCount; ++i)
  {
    const std::size_t slot = slotOf(static_cast<std::uint32_t>(i));
    pointCones[i] = cones[slot].withCosine(axes[slot] == glm::dvec3(0.0) ? noCone : least[slot]);
  }
  return pointCones;
}

/// Whether the process has begun to exit. ParaView deletes its filters as its own libraries
/// are unloaded at exit, after Embree's static state has gone: a release then locks a mutex
/// that Embree has freed, which threw ("pthread_mutex_lock failed") or, once the memory was
/// reused, waited forever (pvpython hung after tests/paraview_plugin_check.py's last check).
std::atomic<bool> processExiting{ false };

/// Registered after Embree is loaded, so that it runs before Embree's static destructors
/// (exit runs its handlers last registered, first run).
void watchForExit()
{
  static const bool watching = std::atexit([] { processExiting = true; }) == 0;
  (void)watching;
}
}

/// The Embree device and scene, kept out of the header so that users of OccluderMesh need no
/// Embree headers.
struct OccluderMesh::Embree
{
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;

  ~Embree()
  {
    // Once the process is exiting, Embree may be gone (watchForExit); what would be released
    // then no longer matters.
    if (processExiting)
    {
      return;
    }
    if (scene)
    {
      rtcReleaseScene(scene);
    }
    if (device)
    {
      rtcReleaseDevice(device);
    }
  }

  /// The scene to trace; throws once releaseTracing() has freed it.
  RTCScene traced() const
  {
    if (!scene)
    {
      throw std::logic_error("OccluderMesh: a ray traced after releaseTracing()");
    }
    return scene;
  }

  /// Throws what Embree reports as its last error, if anything.
  void check(const char* step) const
  {
    const RTCError error = rtcGetDeviceError(device);
    if (error != RTC_ERROR_NONE)
    {
      throw std::runtime_error(std::string("Embree failed to ") + step + " (error " + std::to_string(int(error)) + ")");
    }
  }
};

OccluderMesh::OccluderMesh(UnitFrame frame, const PolygonList& polygons)
  : frame_(std::move(frame))
{
  const std::size_t pointCount = frame_.vertices.size() / 3;
  if (pointCount > std::numeric_limits<std::uint32_t>::max())
  {
    throw std::length_error("more than 2^32 points: too many for the ray casting's triangle list");
  }
  for (std::size_t k = 0; k < polygons.count; ++k)
  {
    const PointId* ids = polygons.ids(k);
    for (std::size_t i = 2; i < polygons.size(k); ++i)
    {
      triangles_.insert(triangles_.end(),
        { static_cast<std::uint32_t>(ids[0]), static_cast<std::uint32_t>(ids[i - 1]),
          static_cast<std::uint32_t>(ids[i]) });
    }
  }
  std::uint32_t groups = 0;
  const std::vector<std::uint32_t> copyGroups = copyGroupsOf(frame_.vertices, pointCount, groups);
  jointNormals_ = jointNormalsOf(frame_.vertices, triangles_, copyGroups, groups);
  ownReach_ = ownReachOf(frame_.vertices, pointCount, triangles_, copyGroups, groups);
  ownNormalCones_ = ownNormalConesOf(frame_.vertices, pointCount, triangles_, copyGroups, groups);
  watchForExit();
  embree_ = std::make_unique<Embree>();
  embree_->device = rtcNewDevice(nullptr);
  if (!embree_->device)
  {
    throw std::runtime_error("Embree could not start (rtcNewDevice failed): does this processor have SSE2?");
  }
  embree_->scene = rtcNewScene(embree_->device);
  if (triangles_.empty())
  {
    rtcCommitScene(embree_->scene); // nothing to hit
    embree_->check("build an empty scene");
    return;
  }
  // Robust: rays through an edge or a corner shared by triangles hit one of them (no leak
  // between watertight triangles), at a small cost.
  rtcSetSceneFlags(embree_->scene, RTC_SCENE_FLAG_ROBUST);
  RTCGeometry geometry = rtcNewGeometry(embree_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  // Shared buffers: Embree reads ShadeLab's arrays, no copy.
  rtcSetSharedGeometryBuffer(
    geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, frame_.vertices.data(), 0, 3 * sizeof(float), pointCount);
  rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, triangles_.data(), 0,
    3 * sizeof(std::uint32_t), triangleCount());
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(embree_->scene, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(embree_->scene);
  embree_->check("build the triangles' BVH");
}

OccluderMesh::NormalCone OccluderMesh::NormalCone::of(const glm::dvec3& unitAxis)
{
  NormalCone cone;
  for (int i = 0; i < 3; ++i)
  {
    cone.axis_[i] = static_cast<std::int16_t>(std::lround(steps * std::clamp(unitAxis[i], -1.0, 1.0)));
  }
  return cone;
}

OccluderMesh::NormalCone OccluderMesh::NormalCone::withCosine(double cosine) const
{
  NormalCone cone = *this;
  // Rounded down: a wider cone than the normals need, never a narrower one.
  cone.cosine_ = static_cast<std::int16_t>(std::floor(steps * std::clamp(cosine, -1.0, 1.0)));
  return cone;
}

glm::dvec3 OccluderMesh::NormalCone::axis() const
{
  const glm::dvec3 stored(axis_[0], axis_[1], axis_[2]);
  const double length = glm::length(stored);
  return length > 0 ? stored / length : glm::dvec3(0.0);
}

OccluderMesh::~OccluderMesh() = default;

void OccluderMesh::checkTracing() const
{
  embree_->check("trace the rays");
}

void OccluderMesh::releaseTracing()
{
  if (embree_->scene)
  {
    rtcReleaseScene(embree_->scene);
    embree_->scene = nullptr;
  }
}

glm::vec3 OccluderMesh::leavingSide(const SurfaceRay& ray) const
{
  glm::vec3 side(ray.side);
  if (ray.vertex >= 0 && static_cast<std::size_t>(ray.vertex) < jointNormals_.size())
  {
    // Off the faces of every copy, on the side the ray leaves from.
    const glm::vec3 joint = jointNormals_[static_cast<std::size_t>(ray.vertex)];
    const float along = glm::dot(joint, side);
    side = along > 0 ? joint : along < 0 ? -joint : side;
  }
  return side;
}

OccluderMesh::FrameRay OccluderMesh::inFrame(const SurfaceRay& ray) const
{
  return { offsetRayOrigin(glm::vec3(frame_.toUnit(ray.point)), leavingSide(ray)), glm::vec3(ray.direction),
    frameDistance(ray.maxDistance) };
}

namespace
{
void setRay(RTCRay& ray, const glm::vec3& origin, const glm::vec3& direction, float maxDistance)
{
  ray.org_x = origin.x;
  ray.org_y = origin.y;
  ray.org_z = origin.z;
  ray.tnear = 0.0f;
  ray.dir_x = direction.x;
  ray.dir_y = direction.y;
  ray.dir_z = direction.z;
  ray.time = 0.0f;
  ray.tfar = maxDistance;
  ray.mask = 0xFFFFFFFFu;
  ray.id = 0;
  ray.flags = 0;
}
}

namespace
{
/// frameRays[0..count-1] (count <= 16) into a packet, valid[j] set for those in use.
void packRays(const OccluderMesh::FrameRay* frameRays, int count, int* valid, RTCRay16& rays)
{
  for (int j = 0; j < 16; ++j)
  {
    valid[j] = j < count ? -1 : 0;
    const OccluderMesh::FrameRay& local = frameRays[j < count ? j : 0];
    rays.org_x[j] = local.origin.x;
    rays.org_y[j] = local.origin.y;
    rays.org_z[j] = local.origin.z;
    rays.tnear[j] = 0.0f;
    rays.dir_x[j] = local.direction.x;
    rays.dir_y[j] = local.direction.y;
    rays.dir_z[j] = local.direction.z;
    rays.time[j] = 0.0f;
    rays.tfar[j] = local.maxDistance;
    rays.mask[j] = 0xFFFFFFFFu;
    rays.id[j] = static_cast<unsigned>(j);
    rays.flags[j] = 0;
  }
}
}

unsigned OccluderMesh::occluded(const FrameRay* frameRays, int count) const
{
  static_assert(bundleSize == 16, "the bundle is an RTCRay16");
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  if (count == 1)
  {
    const FrameRay& local = frameRays[0];
    RTCRay ray;
    setRay(ray, local.origin, local.direction, local.maxDistance);
    rtcOccluded1(embree_->traced(), &context, &ray);
    return ray.tfar < 0 ? 1u : 0u; // Embree sets it to -inf on a hit
  }
  alignas(64) int valid[16];
  RTCRay16 rays;
  packRays(frameRays, count, valid, rays);
  rtcOccluded16(valid, embree_->traced(), &context, &rays);
  unsigned blocked = 0;
  for (int j = 0; j < count; ++j)
  {
    blocked |= rays.tfar[j] < 0 ? 1u << j : 0u;
  }
  return blocked;
}

glm::dvec3 OccluderMesh::areaVector(std::size_t triangle) const
{
  return areaVectorOf(frame_.vertices, &triangles_[3 * triangle]);
}

void OccluderMesh::firstHits(const FrameRay* frameRays, int count, RayHit* hits) const
{
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  alignas(64) int valid[16];
  RTCRayHit16 rayHits;
  packRays(frameRays, count, valid, rayHits.ray);
  for (int j = 0; j < 16; ++j)
  {
    rayHits.hit.geomID[j] = RTC_INVALID_GEOMETRY_ID;
    rayHits.hit.instID[0][j] = RTC_INVALID_GEOMETRY_ID;
  }
  rtcIntersect16(valid, embree_->traced(), &context, &rayHits);
  for (int j = 0; j < count; ++j)
  {
    hits[j] = rayHits.hit.geomID[j] == RTC_INVALID_GEOMETRY_ID
      ? RayHit{}
      : RayHit{ rayHits.hit.primID[j], rayHits.hit.u[j], rayHits.hit.v[j] };
  }
}

float OccluderMesh::ownTrianglesReach(const FrameRay& ray, const glm::vec3& unitPoint, PointId vertex) const
{
  if (vertex < 0 || static_cast<std::size_t>(vertex) >= ownReach_.size())
  {
    return ray.maxDistance;
  }
  // A triangle with a corner at the point lies within its reach of the point, so within
  // reach + |origin - point| of the ray's origin; the margin covers float's rounding of the
  // lengths and of the hit's distance.
  const float reach =
    1.001f * (ownReach_[static_cast<std::size_t>(vertex)] + glm::length(ray.origin - unitPoint)) + 1e-6f;
  return std::min(ray.maxDistance, reach);
}

bool OccluderMesh::leavesAllOwnPlanes(const FrameRay& ray, const glm::vec3& unitPoint, std::size_t point) const
{
  if (point >= ownNormalCones_.size() || ownNormalCones_[point].cosine() <= 0)
  {
    return false;
  }
  // Every own triangle's normal n is within the cone: n.v is at least |v| cos(angle(axis, v) +
  // the cone's half-angle). The ray starts on one side of every own plane (they all pass
  // through the point) and moves away from all of them when that bound is positive, with the
  // same sign, for its lift off the point and for its direction. The margins: a cosine of 1e-3
  // (about 0.06 degrees; Embree's normals of the triangles, from the same float corners, differ
  // from ownNormalConesOf's by at most 1e-4 radians), and a lift above the planes of 32 float
  // units of the coordinates and edges involved, far above the rounding of Embree's distances.
  const glm::dvec3 axis = ownNormalCones_[point].axis();
  const double cosine = ownNormalCones_[point].cosine(), sine = std::sqrt(1 - cosine * cosine);
  auto leastCosine = [&](const glm::dvec3& v, double side)
  {
    const double length = glm::length(v);
    const double along = side * glm::dot(axis, v) / length, across = std::sqrt(std::max(0.0, 1 - along * along));
    return length > 0 ? along * cosine - across * sine : -1.0; // cos(angle(axis, v) + half-angle)
  };
  const glm::dvec3 lift = glm::dvec3(ray.origin) - glm::dvec3(unitPoint), direction(ray.direction);
  const glm::dvec3 magnitude = glm::abs(glm::dvec3(unitPoint));
  const double leastLift =
    32 * 0x1p-24 * (std::max({ magnitude.x, magnitude.y, magnitude.z }) + ownReach_[point] + glm::length(lift));
  auto movesAway = [&](double side)
  {
    const double liftCosine = leastCosine(lift, side);
    return liftCosine > 1e-3 && liftCosine * glm::length(lift) > leastLift && leastCosine(direction, side) > 1e-3;
  };
  return movesAway(1) || movesAway(-1);
}

std::int64_t OccluderMesh::firstHit(const FrameRay& ray) const
{
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rayHit;
  setRay(rayHit.ray, ray.origin, ray.direction, ray.maxDistance);
  rayHit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rayHit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(embree_->traced(), &context, &rayHit);
  return rayHit.hit.geomID == RTC_INVALID_GEOMETRY_ID ? -1 : std::int64_t(rayHit.hit.primID);
}

bool OccluderMesh::hasCornerAt(std::size_t t, const glm::vec3& unitPoint) const
{
  for (int i = 0; i < 3; ++i)
  {
    const float* corner = &frame_.vertices[3 * std::size_t(triangles_[3 * t + i])];
    if (corner[0] == unitPoint.x && corner[1] == unitPoint.y && corner[2] == unitPoint.z)
    {
      return true;
    }
  }
  return false;
}

std::int64_t OccluderMesh::firstHitNearby(const FrameRay& ray, const glm::vec3& unitPoint, PointId vertex) const
{
  if (vertex >= 0 && leavesAllOwnPlanes(ray, unitPoint, static_cast<std::size_t>(vertex)))
  {
    return -1; // none of its own triangles is in the ray's way, whatever it meets first
  }
  // The search ends where the point's own triangles end: beyond, a first hit is not its own.
  FrameRay nearby = ray;
  nearby.maxDistance = ownTrianglesReach(ray, unitPoint, vertex);
  return firstHit(nearby);
}

bool OccluderMesh::firstHitHasCorner(const FrameRay& ray, const glm::dvec3& point, PointId vertex) const
{
  // The corners as the BVH holds them, against the point taken into the frame the same way.
  const glm::vec3 unitPoint(frame_.toUnit(point));
  const std::int64_t hit = firstHitNearby(ray, unitPoint, vertex);
  return hit >= 0 && hasCornerAt(std::size_t(hit), unitPoint);
}

bool OccluderMesh::aroundOnItsSurface(
  std::size_t t, PointId vertex, const glm::vec3& point, const glm::dvec3& side) const
{
  for (int i = 0; i < 3; ++i)
  {
    if (PointId(triangles_[3 * t + i]) == vertex)
    {
      return true; // its normal is the mean of this facet's and its neighbours'
    }
  }
  if (!hasCornerAt(t, point))
  {
    return false;
  }
  // A copy's facet: across a UV seam, the same surface; across a hard edge, where a mesh is
  // split at its feature edges (30 degrees by default in vtkPolyDataNormals), another one.
  const glm::dvec3 normal = areaVectorOf(frame_.vertices, &triangles_[3 * t]);
  constexpr double cos30Degrees = 0.86602540378443865;
  return std::abs(glm::dot(normal, side)) >= cos30Degrees * glm::length(normal);
}

double OccluderMesh::ownFacetsRise(const glm::vec3& point, PointId vertex, const glm::dvec3& side) const
{
  // Every triangle with the point or a copy as a corner lies within the point's reach of it.
  struct Query
  {
    const OccluderMesh& mesh;
    glm::vec3 point;
    PointId vertex;
    glm::dvec3 side;
    double rise = 0;
  } query{ *this, point, vertex, side };
  RTCPointQuery sphere;
  sphere.x = point.x;
  sphere.y = point.y;
  sphere.z = point.z;
  sphere.time = 0.0f;
  sphere.radius = 1.001f * ownReach_[static_cast<std::size_t>(vertex)] + 1e-6f;
  RTCPointQueryContext context;
  rtcInitPointQueryContext(&context);
  rtcPointQuery(
    embree_->traced(), &sphere, &context,
    [](RTCPointQueryFunctionArguments* args)
    {
      Query& q = *static_cast<Query*>(args->userPtr);
      const std::size_t t = args->primID;
      if (q.mesh.aroundOnItsSurface(t, q.vertex, q.point, q.side))
      {
        for (int i = 0; i < 3; ++i)
        {
          const glm::dvec3 corner = unitPoint(q.mesh.frame_.vertices, q.mesh.triangles_[3 * t + i]);
          q.rise = std::max(q.rise, glm::dot(corner - glm::dvec3(q.point), q.side));
        }
      }
      return false; // the query sphere stays as it is
    },
    &query);
  return query.rise;
}

bool OccluderMesh::hiddenPastOwnFacets(const SurfaceRay& surfaceRay) const
{
  const glm::vec3 start(frame_.toUnit(surfaceRay.point));
  const glm::dvec3 side(leavingSide(surfaceRay));
  FrameRay ray = inFrame(surfaceRay);
  if (surfaceRay.vertex < 0 || static_cast<std::size_t>(surfaceRay.vertex) >= ownReach_.size())
  {
    return true; // a point without facets of its own: what blocks the ray is something else
  }
  const std::int64_t hit = firstHitNearby(ray, start, surfaceRay.vertex);
  if (hit < 0 || !aroundOnItsSurface(std::size_t(hit), surfaceRay.vertex, start, side))
  {
    return true;
  }
  // From above every corner of the point's facets, a ray that leaves their side meets none of
  // them (nor any facet between them); the light is retargeted from there.
  const double lift = ownFacetsRise(start, surfaceRay.vertex, side);
  const glm::dvec3 light = glm::dvec3(start) + glm::dvec3(ray.direction) * double(ray.maxDistance);
  ray.origin = offsetRayOrigin(glm::vec3(glm::dvec3(start) + lift * side), glm::vec3(side));
  if (!std::isinf(ray.maxDistance))
  {
    const glm::dvec3 toLight = light - glm::dvec3(ray.origin);
    ray.maxDistance = static_cast<float>(glm::length(toLight));
    ray.direction = glm::vec3(toLight / glm::length(toLight));
  }
  return occluded(&ray, 1) != 0;
}
}
