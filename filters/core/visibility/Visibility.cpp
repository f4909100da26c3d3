#include "Visibility.h"

#include "MonteCarloEstimate.h"
#include "SampleWarps.h"
#include "Vec3.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace shadelab
{
namespace
{
/// The seeds of ambient occlusion's samples and of the sky view factor's, apart from every
/// light's (lights use their index) and from each other (each takes three streams).
constexpr std::uint64_t occlusionSeed = 0x414f'0000'0000'0000ull;
constexpr std::uint64_t skyViewSeed = occlusionSeed + 0x10;
/// The seed of interreflection's gather rays, apart from those.
constexpr std::uint64_t gatherSeed = 0x4952'0000'0000'0000ull;

/// The points of the unit square that one vertex's rays are warped from. Independent: uniform.
/// Stratified: two to a cell of a grid of samples / 2 cells, consecutive points sharing a cell
/// (an odd last one anywhere), so that the standard error, which pairs consecutive samples
/// (MonteCarloEstimate.h), pairs samples of one stratum and is unbiased. With one sample per
/// cell it paired neighbouring cells and erred high: 86% of the errors within one standard
/// error, on the plane under a sphere (test Visibility.ASphereOccludesThePlaneBelowByItsFormFactor).
class RaySamples
{
public:
  /// firstSample: where this round starts among the vertex's samples (even).
  RaySamples(std::uint64_t seed, PointId vertex, const Sampling& sampling, int firstSample = 0)
    : count_(sampling.samples)
    , stratified_(sampling.stratified)
    , first_(seed, static_cast<std::uint64_t>(vertex), { std::max(1, count_ / 2), true }, firstSample / 2)
    , second_(seed + 1, static_cast<std::uint64_t>(vertex), { std::max(1, count_ / 2), true }, firstSample / 2)
    , independent_(seed + 2, static_cast<std::uint64_t>(vertex), { count_, false }, firstSample)
  {
  }

  int count() const { return count_; }

  /// Points first .. first + count - 1 (first even) into x[] and y[]: consecutive pairs from
  /// the two stratified sequences, an odd last one from the independent one.
  void points(int first, int count, double* x, double* y) const
  {
    if (!stratified_)
    {
      independent_.points(first, count, x, y);
      return;
    }
    constexpr int most = OccluderMesh::bundleSize / 2;
    double evenX[most], evenY[most], oddX[most], oddY[most];
    first_.points(first / 2, (count + 1) / 2, evenX, evenY);
    second_.points(first / 2, count / 2, oddX, oddY);
    for (int k = 0; k < count; ++k)
    {
      x[k] = k % 2 == 0 ? evenX[k / 2] : oddX[k / 2];
      y[k] = k % 2 == 0 ? evenY[k / 2] : oddY[k / 2];
    }
    if (count_ % 2 == 1 && first + count == count_)
    {
      const glm::dvec2 last = independent_.point(count_ - 1);
      x[count - 1] = last.x;
      y[count - 1] = last.y;
    }
  }

private:
  int count_;
  bool stratified_;
  SampleSequence first_, second_, independent_;
};

bool hasNormal(const RayVertex& vertex)
{
  return vertex.normal != glm::dvec3(0.0);
}

/// Whether a ray along `direction` meets the hit triangle on its front: the side its shading
/// normals, interpolated at the hit, point to. The side the ray meets is the triangle's own
/// (its area vector's); the normals only name which side is the front. (Asking the normal
/// itself would turn a ray that grazes a facet onto its neighbour's front into a back where
/// the smooth normal leans away from the facets: a tenth of a percent of a sphere's rays.)
template<typename Real>
bool arrivesOnFront(const OccluderMesh& occluders, PackedPoints<Real> normals, const OccluderMesh::RayHit& hit,
  const glm::dvec3& direction)
{
  const std::array<std::uint32_t, 3> corners = occluders.corners(hit.triangle);
  const glm::dvec3 normal = (1.0 - double(hit.u) - double(hit.v)) * normals(PointId(corners[0])) +
    double(hit.u) * normals(PointId(corners[1])) + double(hit.v) * normals(PointId(corners[2]));
  const glm::dvec3 area = occluders.areaVector(hit.triangle);
  return (glm::dot(area, normal) > 0) != (glm::dot(area, direction) > 0);
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

/// Casts a ray along direction(u) for each sample point u, in bundles that share their start,
/// and calls onBundle(rays, first, count, x, y, z) for each: the bundle's rays, where they are
/// among the samples, and their directions as arrays of coordinates.
template<typename Direction, typename OnBundle>
void forEachBundle(const OccluderMesh& occluders, const RayVertex& vertex, const RaySamples& samples,
  double maxDistance, Direction direction, OnBundle onBundle)
{
  OccluderMesh::FrameRay rays[OccluderMesh::bundleSize];
  std::fill(std::begin(rays), std::end(rays),
    occluders.inFrame({ vertex.position, vertex.normal, {}, maxDistance, vertex.id }));
  for (int first = 0; first < samples.count(); first += OccluderMesh::bundleSize)
  {
    const int count = std::min(OccluderMesh::bundleSize, samples.count() - first);
    // The directions in arrays of their coordinates, a loop that vectorizes, then into rays.
    double x[OccluderMesh::bundleSize], y[OccluderMesh::bundleSize], z[OccluderMesh::bundleSize];
    warpedPoints(samples, first, count, direction, x, y, z);
    for (int j = 0; j < count; ++j)
    {
      rays[j].direction = glm::vec3(glm::dvec3(x[j], y[j], z[j]));
    }
    onBundle(rays, first, count, x, y, z);
  }
}

/// Casts a ray along direction(u) for each sample point u, in bundles, and calls
/// seen(direction, hidden) for each in sample order. The rays share their start.
template<typename Direction, typename Seen>
void forEachRay(const OccluderMesh& occluders, const RayVertex& vertex, const RaySamples& samples, double maxDistance,
  Direction direction, Seen seen)
{
  forEachBundle(occluders, vertex, samples, maxDistance, direction,
    [&](const OccluderMesh::FrameRay* rays, int, int count, const double* x, const double* y, const double* z)
    {
      const unsigned hidden = occluders.occluded(rays, count);
      for (int j = 0; j < count; ++j)
      {
        seen(glm::dvec3(x[j], y[j], z[j]), ((hidden >> j) & 1u) != 0);
      }
    });
}

/// The standard error of a fraction of open rays (MonteCarloEstimate's, of 0s and 1s) after
/// `rays` rays. The pairs' variance is D / N^2 for D pairs that disagree, a small count, and a
/// count of 0 to 2 where the silhouette crosses a few cells understates the error (98.7% within
/// three standard errors on the plane under a sphere). One ray's variance is added:
/// (D + 1) / N^2, the mean of a count's rate given D under a flat prior. Never below 1 / N,
/// one ray's weight.
double openFractionError(const MonteCarloMean<double>& open, int rays)
{
  return std::hypot(open.standardError(), 1.0 / rays);
}

/// Casts the vertex's rays of one estimate (sample points from `seed`), calling
/// seen(direction, hidden) for each in sample order: settings' fixed count in one round or,
/// with a target, rounds until the open fraction in `open` meets it (SequentialSampling.h).
/// Returns how many rays were cast.
template<typename Direction, typename Seen>
int drawRays(const OccluderMesh& occluders, const RayVertex& vertex, std::uint64_t seed,
  const OcclusionSettings& settings, const MonteCarloMean<double>& open, Direction direction, Seen seen)
{
  if (!settings.target)
  {
    forEachRay(
      occluders, vertex, RaySamples(seed, vertex.id, settings.sampling), settings.maxDistance, direction, seen);
    return settings.sampling.samples;
  }
  int drawn = 0;
  for (int round = settings.target->nextRound(0, 0); round > 0;
       round = settings.target->nextRound(drawn, openFractionError(open, drawn)))
  {
    const RaySamples samples(seed, vertex.id, { round, settings.sampling.stratified }, drawn);
    forEachRay(occluders, vertex, samples, settings.maxDistance, direction, seen);
    drawn += round;
  }
  return drawn;
}
}

void lightVisibility(const OccluderMesh& occluders, const RayVertex* vertices, const LightDirection* directions,
  int count, bool twoSided, LightVisibility* visibility, SelfShadowing selfShadowing)
{
  SurfaceRay surfaceRays[OccluderMesh::bundleSize];
  OccluderMesh::FrameRay rays[OccluderMesh::bundleSize];
  int cast[OccluderMesh::bundleSize]; // the vertex of each ray
  int rayCount = 0;
  auto trace = [&]
  {
    const unsigned hidden = rayCount > 0 ? occluders.occluded(rays, rayCount) : 0u;
    for (int j = 0; j < rayCount; ++j)
    {
      const RayVertex& vertex = vertices[cast[j]];
      LightVisibility& seen = visibility[cast[j]];
      seen.visible = ((hidden >> j) & 1u) == 0;
      seen.blockedByOwnTriangle = !seen.visible && occluders.firstHitHasCorner(rays[j], vertex.position, vertex.id);
      if (seen.blockedByOwnTriangle && selfShadowing == SelfShadowing::SmoothSurface)
      {
        seen.visible = !occluders.hiddenPastOwnFacets(surfaceRays[j]);
      }
    }
    rayCount = 0;
  };
  for (int k = 0; k < count; ++k)
  {
    const RayVertex& vertex = vertices[k];
    const double cosine = glm::dot(vertex.normal, directions[k].toLight);
    visibility[k] = {};
    if (hasNormal(vertex) && cosine != 0 && (cosine > 0 || twoSided))
    {
      surfaceRays[rayCount] = { vertex.position, cosine > 0 ? vertex.normal : -vertex.normal, directions[k].toLight,
        directions[k].distance, vertex.id };
      rays[rayCount] = occluders.inFrame(surfaceRays[rayCount]);
      cast[rayCount++] = k;
      if (rayCount == OccluderMesh::bundleSize)
      {
        trace();
      }
    }
  }
  trace();
}

int HiddenSampleTracer::add(
  const ShadowedLightEstimator& light, const SurfacePoint& point, PointId vertex, std::uint64_t* words)
{
  const int count = light.shadowRayCount();
  rays_.resize(static_cast<std::size_t>(count));
  light.shadowRays(point, rays_.data());
  // The rays differ only in direction and length: the start is moved off the surface once.
  const SurfaceRay from{ point.position, point.normal, {}, 0.0, vertex };
  return addRays(from, occluders_.inFrame(from), rays_.data(), count, words);
}

int HiddenSampleTracer::addRays(
  const SurfaceRay& from, const OccluderMesh::FrameRay& start, const ShadowRay* rays, int count, std::uint64_t* words)
{
  std::fill_n(words, hiddenSampleWords(count), 0u);
  int cast = 0;
  for (int j = 0; j < count; ++j)
  {
    if (!rays[j].cast)
    {
      continue;
    }
    packet_[queued_] = { start.origin, glm::vec3(rays[j].direction), occluders_.frameDistance(rays[j].distance) };
    surfaceRays_[queued_] = { from.point, from.side, rays[j].direction, rays[j].distance, from.vertex };
    wordOf_[queued_] = &words[j / 64];
    bitOf_[queued_++] = j % 64;
    ++cast;
    if (queued_ == OccluderMesh::bundleSize)
    {
      flush();
    }
  }
  return cast;
}

void HiddenSampleTracer::flush()
{
  const unsigned hidden = queued_ > 0 ? occluders_.occluded(packet_, queued_) : 0u;
  for (int j = 0; j < queued_; ++j)
  {
    const bool blocked = ((hidden >> j) & 1u) != 0 &&
      (selfShadowing_ == SelfShadowing::Facets || occluders_.hiddenPastOwnFacets(surfaceRays_[j]));
    *wordOf_[j] |= std::uint64_t(blocked) << bitOf_[j];
  }
  queued_ = 0;
}

RoundShadowTracer::RoundShadowTracer(
  const OccluderMesh& occluders, const SurfacePoint& point, PointId vertex, SelfShadowing selfShadowing)
  : tracer_(occluders, selfShadowing)
  , from_{ point.position, point.normal, {}, 0.0, vertex }
  , start_(occluders.inFrame(from_))
{
}

HiddenSamples RoundShadowTracer::trace(const ShadowRay* rays, int count)
{
  words_.resize(static_cast<std::size_t>(hiddenSampleWords(count)));
  cast_ += static_cast<std::uint64_t>(tracer_.addRays(from_, start_, rays, count, words_.data()));
  tracer_.flush();
  return { words_.data() };
}

void hiddenSamples(const OccluderMesh& occluders, const ShadowedLightEstimator& light, const SurfacePoint& point,
  PointId vertex, std::uint64_t* words, SelfShadowing selfShadowing)
{
  HiddenSampleTracer tracer(occluders, selfShadowing);
  tracer.add(light, point, vertex, words);
  tracer.flush();
}

bool enclosesPoint(const OccluderMesh& occluders, const glm::dvec3& point)
{
  static_assert(enclosureRays % OccluderMesh::bundleSize == 0, "the rays go in whole bundles");
  // The Fibonacci sphere's points: evenly spread, the same every run (R. Swinbank and R. J.
  // Purser, "Fibonacci grids", Q. J. R. Meteorol. Soc. 132, 2006).
  const double goldenAngle = samplePi * (3 - std::sqrt(5.0));
  const OccluderMesh::FrameRay start = occluders.inFrame({ point, glm::dvec3(0.0), {}, 0.0, -1 });
  OccluderMesh::FrameRay bundle[OccluderMesh::bundleSize];
  for (int first = 0; first < enclosureRays; first += OccluderMesh::bundleSize)
  {
    for (int j = 0; j < OccluderMesh::bundleSize; ++j)
    {
      const int k = first + j;
      const double z = 1 - (2 * k + 1) / double(enclosureRays);
      const double r = std::sqrt(1 - z * z);
      const glm::dvec3 direction(r * std::cos(goldenAngle * k), r * std::sin(goldenAngle * k), z);
      bundle[j] = { start.origin, glm::vec3(direction), std::numeric_limits<float>::infinity() };
    }
    if (occluders.occluded(bundle, OccluderMesh::bundleSize) != (1u << OccluderMesh::bundleSize) - 1)
    {
      return false;
    }
  }
  return true;
}

OcclusionEstimate ambientOcclusion(
  const OccluderMesh& occluders, const RayVertex& vertex, const OcclusionSettings& settings)
{
  OcclusionEstimate estimate;
  if (!hasNormal(vertex))
  {
    return estimate;
  }
  MonteCarloMean<double> open(settings.sampling.stratified);
  glm::dvec3 openDirections(0.0);
  estimate.rays = drawRays(
    occluders, vertex, occlusionSeed, settings, open,
    [&](const glm::dvec2& u) { return cosineWeightedDirection(vertex.normal, u).direction; },
    [&](const glm::dvec3& direction, bool hidden)
    {
      open.add(hidden ? 0.0 : 1.0);
      openDirections += hidden ? glm::dvec3(0.0) : direction;
    });
  estimate.occlusion = open.mean();
  estimate.standardError = openFractionError(open, estimate.rays);
  if (settings.bentNormal && openDirections != glm::dvec3(0.0))
  {
    estimate.bentNormal = glm::normalize(openDirections);
  }
  if (settings.skyViewFactor)
  {
    MonteCarloMean<double> unblocked(settings.sampling.stratified);
    drawRays(
      occluders, vertex, skyViewSeed, settings, unblocked,
      [&](const glm::dvec2& u) { return uniformHemisphereDirection(vertex.normal, u); },
      [&](const glm::dvec3&, bool hidden) { unblocked.add(hidden ? 0.0 : 1.0); });
    estimate.skyViewFactor = unblocked.mean();
  }
  return estimate;
}

template<typename Real>
int gatherHits(const OccluderMesh& occluders, const RayVertex& vertex, const Sampling& sampling,
  PackedPoints<Real> normals, OccluderMesh::RayHit* hits, TriangleBacks backs)
{
  if (!hasNormal(vertex))
  {
    std::fill(hits, hits + sampling.samples, OccluderMesh::RayHit{});
    return 0;
  }
  int backHits = 0;
  forEachBundle(
    occluders, vertex, RaySamples(gatherSeed, vertex.id, sampling), std::numeric_limits<double>::infinity(),
    [&](const glm::dvec2& u) { return cosineWeightedDirection(vertex.normal, u).direction; },
    [&](const OccluderMesh::FrameRay* rays, int first, int count, const double* x, const double* y, const double* z)
    {
      occluders.firstHits(rays, count, hits + first);
      for (int j = 0; j < count; ++j)
      {
        OccluderMesh::RayHit& hit = hits[first + j];
        if (hit.triangle != OccluderMesh::RayHit::noTriangle &&
          !arrivesOnFront(occluders, normals, hit, glm::dvec3(x[j], y[j], z[j])))
        {
          hit.onBack = true;
          hit = backs == TriangleBacks::Lit ? hit : OccluderMesh::RayHit{};
          ++backHits;
        }
      }
    });
  return backHits;
}

template int gatherHits(
  const OccluderMesh&, const RayVertex&, const Sampling&, PackedPoints<float>, OccluderMesh::RayHit*, TriangleBacks);
template int gatherHits(
  const OccluderMesh&, const RayVertex&, const Sampling&, PackedPoints<double>, OccluderMesh::RayHit*, TriangleBacks);

std::vector<int> quarterOfGatherRays(const Sampling& sampling)
{
  std::vector<int> kept;
  const int pairs = sampling.samples / 2; // RaySamples: pair m's two rays share cell m
  const int columns = SampleSequence::gridColumns(std::max(1, pairs));
  for (int j = 0; j < sampling.samples; ++j)
  {
    const int cell = j / 2;
    const bool checkerboard = j % 2 == 0 && cell < pairs && (cell / columns + cell % columns) % 2 == 0;
    if (sampling.samples < 32 || (sampling.stratified ? checkerboard : j % 4 == 0))
    {
      kept.push_back(j);
    }
  }
  return kept;
}
}
