#pragma once
// What a vertex sees of a light and of the sky past the mesh itself (docs/formulas.md
// section 20): the visibility of a local light, 0 or 1, and ambient occlusion, the
// cosine-weighted fraction of the hemisphere above the vertex from which no triangle blocks
// the sky.
#include "DistributedLight.h"
#include "LightEvaluation.h"
#include "OccluderMesh.h"
#include "SampleSequence.h"
#include "SelfShadowing.h"
#include "SequentialSampling.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

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
  /// The ray's first hit is a triangle that has the vertex, or a copy of it at a seam, as a
  /// corner: a concave crease, or, on a coarse mesh, a light the smooth normal faces but a
  /// neighbouring facet hides (the shadow terminator). Under SelfShadowing::SmoothSurface the
  /// light may still be visible.
  bool blockedByOwnTriangle = false;
};

/// How many consecutive vertices the visibility step takes at a time: their rays to a light
/// share packets, which neighbours' rays fill (where only the vertices that face a light, or
/// the samples that can carry its light, cast a ray, one vertex's rays fill a packet in part).
constexpr int rayVertexGroup = 64;

/// The visibility of a light from vertices[0..count-1], into visibility. The rays that are cast
/// go into full packets in vertex order (neighbours' rays to one light begin alike). Each ray
/// leaves on the side of the normal that faces the light; where the light is on the normal's
/// back side and the material is not two-sided, or the vertex has no normal, no ray is cast and
/// the light counts as hidden (the surface itself hides it, and the terms it multiplies are 0
/// there). selfShadowing says whether the vertex's own facets hide a light (SelfShadowing.h).
void lightVisibility(const OccluderMesh& occluders, const RayVertex* vertices, const LightDirection* directions,
  int count, bool twoSided, LightVisibility* visibility, SelfShadowing selfShadowing = SelfShadowing::SmoothSurface);

/// The samples of shadowed area lights or maps that the mesh hides from surface points, as the
/// bits of HiddenSamples: the rays of several points gathered into full packets, each ray's
/// answer set as its sample's bit. Embree answers a ray alike in whatever packet carries it
/// (robust mode; test Visibility.EmbreeAnswersARayAlikeInAnyPacket), so the bits do not
/// depend on which points share a packet.
class HiddenSampleTracer
{
public:
  explicit HiddenSampleTracer(const OccluderMesh& occluders, SelfShadowing selfShadowing = SelfShadowing::SmoothSurface)
    : occluders_(occluders)
    , selfShadowing_(selfShadowing)
  {
  }
  HiddenSampleTracer(const HiddenSampleTracer&) = delete;
  HiddenSampleTracer& operator=(const HiddenSampleTracer&) = delete;

  /// Clears words[0..hiddenSampleWords(light.shadowRayCount())-1] and queues the rays of the
  /// point (the kernel's point: its normal turned toward the viewer where two-sided), which
  /// leave on the side of point.normal; vertex is the point's id in the occluders (for its
  /// copies at seams). Their bits are set when their packet is traced, by flush() at the
  /// latest. Returns how many rays the point casts.
  int add(const ShadowedLightEstimator& light, const SurfacePoint& point, PointId vertex, std::uint64_t* words);
  /// The same for rays[0..count-1] from the surface point `from` (its direction and distance
  /// unused), whose start off the surface is `start` (occluders.inFrame(from)).
  int addRays(const SurfaceRay& from, const OccluderMesh::FrameRay& start, const ShadowRay* rays, int count,
    std::uint64_t* words);
  /// Traces the rays still queued: after it, every added point's bits are set.
  void flush();

private:
  const OccluderMesh& occluders_;
  SelfShadowing selfShadowing_;
  std::vector<ShadowRay> rays_; // one point's rays, as the light names them
  OccluderMesh::FrameRay packet_[OccluderMesh::bundleSize];
  SurfaceRay surfaceRays_[OccluderMesh::bundleSize]; // the queued rays as they leave the surface
  std::uint64_t* wordOf_[OccluderMesh::bundleSize];  // where each queued ray's answer goes
  int bitOf_[OccluderMesh::bundleSize];
  int queued_ = 0;
};

/// A vertex's shadow rays traced a round at a time (RoundShadows), for an estimator drawn to a
/// target: each round's rays in packets of their own, from the point moved off its surface
/// once. Embree's answer to a ray does not depend on its packet, so the bits are those that
/// HiddenSampleTracer gives the same rays.
class RoundShadowTracer final : public RoundShadows
{
public:
  /// point: the kernel's point, whose rays leave on the side of point.normal; vertex: its id in
  /// the occluders (for its copies at seams).
  RoundShadowTracer(const OccluderMesh& occluders, const SurfacePoint& point, PointId vertex,
    SelfShadowing selfShadowing = SelfShadowing::SmoothSurface);
  HiddenSamples trace(const ShadowRay* rays, int count) override;
  /// How many rays it has cast.
  std::uint64_t cast() const { return cast_; }

private:
  HiddenSampleTracer tracer_;
  SurfaceRay from_;
  OccluderMesh::FrameRay start_;
  std::vector<std::uint64_t> words_;
  std::uint64_t cast_ = 0;
};

/// The hidden samples of one point, traced at once (HiddenSampleTracer).
void hiddenSamples(const OccluderMesh& occluders, const ShadowedLightEstimator& light, const SurfacePoint& point,
  PointId vertex, std::uint64_t* words, SelfShadowing selfShadowing = SelfShadowing::SmoothSurface);

/// Whether the mesh encloses the point: every one of enclosureRays rays from it, spread evenly
/// over the sphere, meets a triangle. Then a light there is hidden from every vertex outside
/// (a light inside a closed mesh), which the visibility step flags (FlagLightEnclosed).
constexpr int enclosureRays = 64;
bool enclosesPoint(const OccluderMesh& occluders, const glm::dvec3& point);

/// How ambient occlusion is estimated.
struct OcclusionSettings
{
  /// The rays per vertex and whether they are stratified; with a target, the rays are drawn in
  /// rounds of their own count, each stratified, until the target is met (SequentialSampling.h).
  Sampling sampling{ 64, true };
  std::optional<SamplingTarget> target;
  /// Occluders farther than this from the vertex do not count (infinite: all count).
  double maxDistance = std::numeric_limits<double>::infinity();
  bool skyViewFactor = false; // also the uniformly weighted fraction, with rays of its own
  bool bentNormal = false;    // also the mean unoccluded direction
};

struct OcclusionEstimate
{
  double occlusion = 1;         // the cosine-weighted unoccluded fraction: 1 under an open sky
  double standardError = 0;     // of occlusion
  glm::dvec3 bentNormal{ 0.0 }; // unit; (0, 0, 0) where every ray is blocked or not asked for
  double skyViewFactor = 1;     // the uniformly weighted fraction, when asked for
  int rays = 0; // cast for occlusion (as many again for the sky view factor, or its own count with a target)
};

/// Ambient occlusion at the vertex: settings.sampling.samples cosine-weighted directions about
/// its normal, or with a target as many as it takes, each vertex with its own pattern (a hash
/// of its id and the sample), so that the estimate is the same bits on any number of threads.
/// A vertex without a normal gets the open sky's values: 1, standard error 0, no bent normal,
/// no rays.
OcclusionEstimate ambientOcclusion(
  const OccluderMesh& occluders, const RayVertex& vertex, const OcclusionSettings& settings);

/// What a gather ray that meets a triangle's back brings: nothing, where only the side the
/// normals point to is shaded; that side's radiosity, where both sides are (a two-sided material).
enum class TriangleBacks
{
  Dark,
  Lit
};

/// Interreflection's gather at a vertex (docs/formulas.md section 23): sampling.samples
/// cosine-weighted rays about its normal, stratified in pairs as ambient occlusion's are but
/// from a pattern of their own (seeded by the vertex's id, so the same on any thread or
/// process), and each ray's first hit into hits[0..samples-1] in sample order. A ray that
/// meets the back of a triangle, the side its shading normals (normals, per point) point away
/// from, left into the solid or sees the inside of an open mesh: with dark backs it reads as a
/// miss, with lit ones as a hit marked onBack. Returns how many did. A vertex without a normal
/// casts no ray: every hit a miss. The back of a two-sided vertex gathers as a vertex with the
/// opposite normal.
template<typename Real>
int gatherHits(const OccluderMesh& occluders, const RayVertex& vertex, const Sampling& sampling,
  PackedPoints<Real> normals, OccluderMesh::RayHit* hits, TriangleBacks backs = TriangleBacks::Dark);

/// About a quarter of a vertex's gather rays (gatherHits with `sampling`), spread as evenly as
/// all of them: stratified, the first ray of the pairs whose cells make a checkerboard of the
/// pairs' grid, so that every row and column of strata keeps rays (every fourth ray would keep
/// only alternate columns, a biased part of the hemisphere); independent, every fourth. All of
/// them below 32 rays. Their indices, ascending.
std::vector<int> quarterOfGatherRays(const Sampling& sampling);
}
