#include "Interreflection.h"

#include "MonteCarloEstimate.h"
#include "Visibility.h"

#include "NumberText.h"

#include <algorithm>
#include <array>
#include <limits>
#include <mutex>
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

/// The largest albedo over the channels and the vertices.
double largestAlbedo(const Albedo& albedo, std::size_t vertices)
{
  return albedo.perVertex ? *std::max_element(albedo.perVertex, albedo.perVertex + 3 * vertices)
                          : largestComponent(albedo.uniform);
}

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

IndirectIrradiance BounceGather::bounce(
  const Albedo& albedo, const BounceLimit& limit, bool keepBounces, const RangeLoop& loop)
{
  if (limit.most < 1 || firstBounce_.empty())
  {
    throw std::invalid_argument("BounceGather::bounce: at least 1 bounce, once");
  }
  const std::size_t n = firstBounce_.size();
  const double rho = largestAlbedo(albedo, n);
  if (limit.restShare > 0 && !(rho < 1))
  {
    throw std::invalid_argument("an albedo up to " + withDigits(rho, 3) +
      " reflects all the light it receives: no number of bounces bounds what the rest add");
  }
  std::vector<Rgb>().swap(direct_); // the first bounce is gathered: its room is free
  IndirectIrradiance result{ std::move(firstBounce_), std::move(firstBounceError_), {} };
  if (keepBounces)
  {
    result.bounces.push_back(result.irradiance);
  }
  // B_k, B_1 + ... + B_{k-1}, E_k (E_1 is result.irradiance, until the rest is added).
  std::vector<Rgb> radiosity(n), sum(n), gathered(n);
  // B_k = kd E_k; returns the bound on what the bounces past k add.
  auto reflect = [&](const std::vector<Rgb>& irradiance)
  {
    std::mutex largestLock;
    double largest = 0;
    loop(n,
      [&](std::size_t first, std::size_t last)
      {
        double mine = 0;
        for (std::size_t vertex = first; vertex < last; ++vertex)
        {
          radiosity[vertex] = albedo.at(vertex) * irradiance[vertex];
          mine = std::max(mine, largestComponent(radiosity[vertex]));
        }
        const std::lock_guard<std::mutex> lock(largestLock);
        largest = std::max(largest, mine);
      });
    return rho < 1 ? largest * rho / (1 - rho) : std::numeric_limits<double>::infinity();
  };
  int bounce = 1;
  result.restBound = reflect(result.irradiance);
  // Sweep k gathers E_k from B_{k-1} and makes B_k, whose largest value bounds the rest.
  while (bounce < limit.most && !(limit.restShare > 0 && result.restBound <= limit.restShare))
  {
    loop(n,
      [&](std::size_t first, std::size_t last)
      {
        for (std::size_t vertex = first; vertex < last; ++vertex)
        {
          sum[vertex] += radiosity[vertex];
        }
        gatherLater(radiosity.data(), first, last, gathered.data());
      });
    ++bounce;
    if (keepBounces)
    {
      result.bounces.push_back(gathered);
    }
    result.restBound = reflect(gathered);
  }
  result.bounceCount = bounce;
  if (bounce > 1)
  {
    addLaterBounces(sum, radiosity, gathered, result, loop);
  }
  return result;
}

void BounceGather::addLaterBounces(const std::vector<Rgb>& sum, std::vector<Rgb>& rest, std::vector<Rgb>& restError,
  IndirectIrradiance& result, const RangeLoop& loop) const
{
  loop(rest.size(),
    [&](std::size_t first, std::size_t last)
    {
      gatherLater(sum.data(), first, last, rest.data(), restError.data());
      for (std::size_t vertex = first; vertex < last; ++vertex)
      {
        result.irradiance[vertex] += rest[vertex];
        result.standardError[vertex] += restError[vertex];
      }
    });
}
}
