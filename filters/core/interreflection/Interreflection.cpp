#include "Interreflection.h"

#include "MonteCarloEstimate.h"
#include "Visibility.h"

#include <algorithm>
#include <array>
#include <stdexcept>

namespace shadelab
{
namespace
{
/// A mean over rays and its standard error, per channel.
struct GatherEstimate
{
  Rgb mean{ 0.0 };
  Rgb standardError{ 0.0 };
};

/// B at a hit: its triangle's corners' values weighted by the hit's barycentric coordinates.
Rgb radiosityAt(const OccluderMesh& occluders, const Rgb* radiosity, const OccluderMesh::RayHit& hit)
{
  const std::array<std::uint32_t, 3> corners = occluders.corners(hit.triangle);
  const double u = hit.u, v = hit.v;
  return (1.0 - u - v) * radiosity[corners[0]] + u * radiosity[corners[1]] + v * radiosity[corners[2]];
}

/// The irradiance gathered along `count` hits, hitAt(j) the j-th, from `radiosity` (per vertex,
/// B): the mean of B interpolated at each hit (0 for a miss, which gatherHits also makes of a
/// triangle's back), and its standard error (stratified: consecutive rays paired,
/// MonteCarloEstimate.h).
template<typename HitAt>
GatherEstimate meanOverHits(
  const OccluderMesh& occluders, std::size_t count, const Rgb* radiosity, bool stratified, HitAt hitAt)
{
  MonteCarloEstimate mean(stratified);
  for (std::size_t j = 0; j < count; ++j)
  {
    const OccluderMesh::RayHit hit = hitAt(j);
    mean.add(hit.triangle == OccluderMesh::RayHit::noTriangle ? Rgb(0.0) : radiosityAt(occluders, radiosity, hit));
  }
  return { mean.mean(), count > 1 ? mean.standardError() : Rgb(0.0) };
}
}

void serialLoop(std::size_t count, const std::function<void(std::size_t, std::size_t)>& body)
{
  body(0, count);
}

BounceGather::BounceGather(const OccluderMesh& occluders, std::vector<Rgb> directRadiosity, const Sampling& sampling)
  : occluders_(occluders)
  , direct_(std::move(directRadiosity))
  , sampling_(sampling)
  , kept_(quarterOfGatherRays(sampling))
  , firstBounce_(direct_.size())
  , firstBounceError_(direct_.size())
  , keptHits_(direct_.size() * kept_.size())
{
  if (sampling.samples < 2)
  {
    throw std::invalid_argument("BounceGather: a vertex needs at least 2 rays");
  }
  for (Rgb& b : direct_)
  {
    b = glm::max(b, Rgb(0.0));
  }
}

void BounceGather::addVertex(std::size_t vertex, const OccluderMesh::RayHit* hits)
{
  const GatherEstimate first = meanOverHits(occluders_, std::size_t(sampling_.samples), direct_.data(),
    sampling_.stratified, [&](std::size_t j) { return hits[j]; });
  firstBounce_[vertex] = first.mean;
  firstBounceError_[vertex] = first.standardError;
  for (std::size_t k = 0; k < kept_.size(); ++k)
  {
    keptHits_[vertex * kept_.size() + k] = KeptHit::of(hits[kept_[k]]);
  }
}

void BounceGather::gatherLater(
  const Rgb* radiosity, std::size_t first, std::size_t last, Rgb* irradiance, Rgb* standardError) const
{
  for (std::size_t vertex = first; vertex < last; ++vertex)
  {
    const KeptHit* hits = &keptHits_[vertex * kept_.size()];
    const GatherEstimate estimate = meanOverHits(
      occluders_, kept_.size(), radiosity, sampling_.stratified, [&](std::size_t k) { return hits[k].unpacked(); });
    irradiance[vertex] = estimate.mean;
    if (standardError)
    {
      standardError[vertex] = estimate.standardError;
    }
  }
}

IndirectIrradiance BounceGather::bounce(const Albedo& albedo, int bounces, bool keepBounces, const RangeLoop& loop)
{
  if (bounces < 1 || firstBounce_.empty())
  {
    throw std::invalid_argument("BounceGather::bounce: at least 1 bounce, once");
  }
  const std::size_t n = firstBounce_.size();
  std::vector<Rgb>().swap(direct_); // the first bounce is gathered: its room is free
  IndirectIrradiance result{ std::move(firstBounce_), std::move(firstBounceError_), {} };
  if (keepBounces)
  {
    result.bounces.push_back(result.irradiance);
  }
  if (bounces == 1)
  {
    return result;
  }
  // B_{k-1}, B_1 + ... + B_{k-1}, E_{k-1} (E_1 is result.irradiance, until the rest is added).
  std::vector<Rgb> radiosity(n), sum(n), gathered(n);
  auto reflect = [&](const std::vector<Rgb>& irradiance)
  {
    return [&](std::size_t first, std::size_t last)
    {
      for (std::size_t vertex = first; vertex < last; ++vertex)
      {
        radiosity[vertex] = albedo.at(vertex) * irradiance[vertex];
        sum[vertex] += radiosity[vertex];
      }
    };
  };
  loop(n, reflect(result.irradiance)); // B_1
  // Sweep k gathers E_k from B_{k-1} and makes B_k for the sweeps after it. The total needs
  // B_1 .. B_{K-1} only: sweep K is made only to keep E_K apart.
  const int lastSweep = keepBounces ? bounces : bounces - 1;
  for (int bounce = 2; bounce <= lastSweep; ++bounce)
  {
    loop(n, [&](std::size_t first, std::size_t last) { gatherLater(radiosity.data(), first, last, gathered.data()); });
    if (keepBounces)
    {
      result.bounces.push_back(gathered);
    }
    if (bounce < bounces)
    {
      loop(n, reflect(gathered));
    }
  }
  std::vector<Rgb>& rest = gathered;
  std::vector<Rgb>& restError = radiosity; // no longer needed: its room reused
  loop(n,
    [&](std::size_t first, std::size_t last) { gatherLater(sum.data(), first, last, rest.data(), restError.data()); });
  loop(n,
    [&](std::size_t first, std::size_t last)
    {
      for (std::size_t vertex = first; vertex < last; ++vertex)
      {
        result.irradiance[vertex] += rest[vertex];
        result.standardError[vertex] += restError[vertex];
      }
    });
  return result;
}
}
