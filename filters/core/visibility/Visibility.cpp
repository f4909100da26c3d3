#include "Visibility.h"

#include "MonteCarloEstimate.h"
#include "SampleWarps.h"
#include "Vec3.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace shadelab
{
namespace
{
/// The seed of ambient occlusion's samples, apart from every light's (lights use their index).
constexpr std::uint64_t occlusionSeed = 0x414f'0000'0000'0000ull;
/// The sky view factor's samples, apart from the occlusion's.
constexpr std::uint64_t skyViewSeed = occlusionSeed + 1;

bool hasNormal(const RayVertex& vertex)
{
  return vertex.normal != glm::dvec3(0.0);
}

/// A direction uniform over the hemisphere about unit n, from a point of the unit square.
glm::dvec3 uniformHemisphereDirection(const glm::dvec3& n, const glm::dvec2& u)
{
  glm::dvec3 t, b;
  orthonormalBasis(n, t, b);
  const double cosTheta = u.x;
  const double sinTheta = std::sqrt(std::max(0.0, 1 - cosTheta * cosTheta));
  const double phi = 2 * samplePi * u.y;
  return sinTheta * std::cos(phi) * t + sinTheta * std::sin(phi) * b + cosTheta * n;
}

/// Casts a ray along direction(u) for each sample point u, in bundles, and calls
/// seen(direction, hidden) for each in sample order.
template <typename Direction, typename Seen>
void forEachRay(const OccluderMesh& occluders, const RayVertex& vertex, const SampleSequence& samples,
  double maxDistance, Direction direction, Seen seen)
{
  for (int first = 0; first < samples.count(); first += OccluderMesh::bundleSize)
  {
    glm::dvec3 directions[OccluderMesh::bundleSize];
    const int count = std::min(OccluderMesh::bundleSize, samples.count() - first);
    for (int j = 0; j < count; ++j)
    {
      directions[j] = direction(samples.point(first + j));
    }
    SurfaceRay rays[OccluderMesh::bundleSize];
    for (int j = 0; j < count; ++j)
    {
      rays[j] = { vertex.position, vertex.normal, directions[j], maxDistance };
    }
    const unsigned hidden = occluders.occluded(rays, count);
    for (int j = 0; j < count; ++j)
    {
      seen(directions[j], ((hidden >> j) & 1u) != 0);
    }
  }
}
}

void lightVisibility(const OccluderMesh& occluders, const RayVertex* vertices, const LightDirection* directions,
  int count, bool twoSided, LightVisibility* visibility)
{
  SurfaceRay rays[OccluderMesh::bundleSize];
  int cast[OccluderMesh::bundleSize]; // the vertex of each ray
  int rayCount = 0;
  for (int k = 0; k < count; ++k)
  {
    const RayVertex& vertex = vertices[k];
    const double cosine = glm::dot(vertex.normal, directions[k].toLight);
    visibility[k] = {};
    if (hasNormal(vertex) && cosine != 0 && (cosine > 0 || twoSided))
    {
      rays[rayCount] = { vertex.position, cosine > 0 ? vertex.normal : -vertex.normal, directions[k].toLight,
        directions[k].distance };
      cast[rayCount++] = k;
    }
  }
  const unsigned hidden = rayCount > 0 ? occluders.occluded(rays, rayCount) : 0u;
  for (int j = 0; j < rayCount; ++j)
  {
    LightVisibility& seen = visibility[cast[j]];
    seen.visible = ((hidden >> j) & 1u) == 0;
    if (!seen.visible)
    {
      const OccluderMesh::Hit hit = occluders.firstHit(rays[j]);
      const PointId id = vertices[cast[j]].id;
      seen.blockedByOwnTriangle = hit.found && std::find(hit.corners.begin(), hit.corners.end(), id) != hit.corners.end();
    }
  }
}

OcclusionEstimate ambientOcclusion(const OccluderMesh& occluders, const RayVertex& vertex, const OcclusionSettings& settings)
{
  OcclusionEstimate estimate;
  if (!hasNormal(vertex))
  {
    return estimate;
  }
  const SampleSequence samples(occlusionSeed, static_cast<std::uint64_t>(vertex.id), settings.sampling);
  MonteCarloEstimate open(settings.sampling.stratified);
  glm::dvec3 openDirections(0.0);
  forEachRay(occluders, vertex, samples, settings.maxDistance,
    [&](const glm::dvec2& u) { return cosineWeightedDirection(vertex.normal, u).direction; },
    [&](const glm::dvec3& direction, bool hidden)
    {
      open.add(Rgb(hidden ? 0.0 : 1.0));
      openDirections += hidden ? glm::dvec3(0.0) : direction;
    });
  estimate.occlusion = open.mean().x;
  estimate.standardError = samples.count() >= 2 ? open.standardError().x : 0.0;
  if (settings.bentNormal && openDirections != glm::dvec3(0.0))
  {
    estimate.bentNormal = glm::normalize(openDirections);
  }
  if (settings.skyViewFactor)
  {
    const SampleSequence skySamples(skyViewSeed, static_cast<std::uint64_t>(vertex.id), settings.sampling);
    int unblocked = 0;
    forEachRay(occluders, vertex, skySamples, settings.maxDistance,
      [&](const glm::dvec2& u) { return uniformHemisphereDirection(vertex.normal, u); },
      [&](const glm::dvec3&, bool hidden) { unblocked += hidden ? 0 : 1; });
    estimate.skyViewFactor = double(unblocked) / skySamples.count();
  }
  return estimate;
}
}
