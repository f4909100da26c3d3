#pragma once
// What a vertex sees of a light and of the sky past the mesh itself (docs/formulas.md
// section 20): the visibility of a local light, 0 or 1, and ambient occlusion, the
// cosine-weighted fraction of the hemisphere above the vertex from which no triangle blocks
// the sky.
#include "DistributedLight.h"
#include "OccluderMesh.h"
#include "SampleSequence.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <limits>

namespace shadelab
{
/// A vertex as the rays see it: its position, its unit shading normal (0 where it has none)
/// and its point id (which seeds its samples).
struct RayVertex
{
  glm::dvec3 position{ 0.0 };
  glm::dvec3 normal{ 0.0 };
  PointId id = 0;
};

/// Whether the light at unit direction toLight and distance (infinite for a distant light) is
/// visible from the vertex.
struct LightVisibility
{
  bool visible = false;
  /// Blocked by a triangle that has the vertex, or a copy of it at a seam, as a corner: a
  /// concave crease, or, on a coarse mesh, a light the smooth normal faces but a neighbouring
  /// facet hides (the shadow terminator).
  bool blockedByOwnTriangle = false;
};

/// Where a light is seen from a vertex: its unit direction, and its distance (infinite for a
/// distant light).
struct LightDirection
{
  glm::dvec3 toLight{ 0.0 };
  double distance = std::numeric_limits<double>::infinity();
};

/// The visibility of a light from vertices[0..count-1] (count <= OccluderMesh::bundleSize,
/// traced as one packet: neighbours' rays to one light begin alike), into visibility. Each
/// ray leaves on the side of the normal that faces the light; where the light is on the
/// normal's back side and the material is not two-sided, or the vertex has no normal, no ray
/// is cast and the light counts as hidden (the surface itself hides it, and the terms it
/// multiplies are 0 there).
void lightVisibility(const OccluderMesh& occluders, const RayVertex* vertices, const LightDirection* directions,
  int count, bool twoSided, LightVisibility* visibility);

/// The samples of a shadowed area light or map that the mesh hides from a surface point (the
/// kernel's point: its normal turned toward the viewer where two-sided), as the bits of HiddenSamples,
/// into words[0..hiddenSampleWords(light.shadowRayCount())-1]. vertex is the point's id in the
/// occluders (for its copies at seams). The rays leave on the side of point.normal, in bundles;
/// rays is scratch space for light.shadowRayCount() rays.
void hiddenSamples(const OccluderMesh& occluders, const ShadowedLightEstimator& light, const SurfacePoint& point,
  PointId vertex, std::vector<ShadowRay>& rays, std::uint64_t* words);

/// Whether the mesh encloses the point: every one of enclosureRays rays from it, spread evenly
/// over the sphere, meets a triangle. Then a light there is hidden from every vertex outside
/// (a light inside a closed mesh), which the visibility step flags (FlagLightEnclosed).
constexpr int enclosureRays = 64;
bool enclosesPoint(const OccluderMesh& occluders, const glm::dvec3& point);

/// How ambient occlusion is estimated.
struct OcclusionSettings
{
  Sampling sampling{ 64, true };
  /// Occluders farther than this from the vertex do not count (infinite: all count).
  double maxDistance = std::numeric_limits<double>::infinity();
  bool skyViewFactor = false; // also the uniformly weighted fraction, with rays of its own
  bool bentNormal = false;    // also the mean unoccluded direction
};

struct OcclusionEstimate
{
  double occlusion = 1;     // the cosine-weighted unoccluded fraction: 1 under an open sky
  double standardError = 0; // of occlusion
  glm::dvec3 bentNormal{ 0.0 }; // unit; (0, 0, 0) where every ray is blocked or not asked for
  double skyViewFactor = 1; // the uniformly weighted fraction, when asked for
};

/// Ambient occlusion at the vertex: settings.sampling.samples cosine-weighted directions about
/// its normal, each vertex with its own pattern (a hash of its id and the sample), so that the
/// estimate is the same bits on any number of threads. A vertex without a normal gets the open
/// sky's values: 1, standard error 0, no bent normal.
OcclusionEstimate ambientOcclusion(const OccluderMesh& occluders, const RayVertex& vertex, const OcclusionSettings& settings);
}
