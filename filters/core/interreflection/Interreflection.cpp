#include "Interreflection.h"

#include "MonteCarloEstimate.h"
#include "Visibility.h"

#include "NumberText.h"

#include <algorithm>
#include <array>
#include <limits>
#include <mutex>
#include <new>
#include <stdexcept>

namespace shadelab
{
namespace
{
/// The largest albedo over the channels and the vertices.
double largestAlbedo(const Albedo& albedo, std::size_t vertices)
{
  return albedo.perVertex ? *std::max_element(albedo.perVertex, albedo.perVertex + 3 * vertices)
                          : largestComponent(albedo.uniform);
}

/// The irradiance gathered along `count` hits, hitAt(j) the j-th, from `radiosity` (B, `fields`
/// per point; a triangle's back reads the points from firstBack on), into mean[0 .. fields - 1]:
/// the mean of each field's B interpolated at each hit from the hit triangle's corners with its
/// barycentric coordinates (0 for a miss, which gatherHits also makes of a dark back), and the
/// light's (field 0's) standard error (stratified: consecutive rays paired, MonteCarloEstimate.h)
/// where standardError is not null.
template<typename HitAt>
void meanOverHits(const OccluderMesh& occluders, std::size_t count, const Rgb* radiosity, std::size_t fields,
  std::size_t firstBack, bool stratified, HitAt hitAt, Rgb* mean, Rgb* standardError)
{
  MonteCarloEstimate light(stratified);
  std::fill(mean + 1, mean + fields, Rgb(0.0));
  for (std::size_t j = 0; j < count; ++j)
  {
    const OccluderMesh::RayHit hit = hitAt(j);
    if (hit.triangle == OccluderMesh::RayHit::noTriangle)
    {
      light.add(Rgb(0.0));
      continue;
    }
    const std::array<std::uint32_t, 3> corners = occluders.corners(hit.triangle);
    const Rgb* side = radiosity + (hit.onBack ? firstBack * fields : 0);
    const double u = hit.u, v = hit.v;
    auto at = [&](std::size_t field)
    {
      return (1.0 - u - v) * side[corners[0] * fields + field] + u * side[corners[1] * fields + field] +
        v * side[corners[2] * fields + field];
    };
    light.add(at(0));
    for (std::size_t field = 1; field < fields; ++field)
    {
      mean[field] += at(field);
    }
  }
  mean[0] = light.mean();
  for (std::size_t field = 1; field < fields; ++field)
  {
    mean[field] /= double(count);
  }
  if (standardError)
  {
    *standardError = count > 1 ? light.standardError() : Rgb(0.0);
  }
}

/// B_0 of every field, each point's light (at least 0: a surface sends out no negative light)
/// followed by its carried fields.
std::vector<Rgb> directOfEveryField(std::vector<Rgb> light, const std::vector<Rgb>& carried)
{
  for (Rgb& b : light)
  {
    b = glm::max(b, Rgb(0.0));
  }
  if (carried.empty())
  {
    return light;
  }
  if (light.empty() || carried.size() % light.size() != 0)
  {
    throw std::invalid_argument("BounceGather: the carried fields must be as many for every point");
  }
  const std::size_t carriedPerPoint = carried.size() / light.size();
  std::vector<Rgb> fields(light.size() + carried.size());
  for (std::size_t point = 0; point < light.size(); ++point)
  {
    Rgb* own = &fields[point * (1 + carriedPerPoint)];
    own[0] = light[point];
    std::copy_n(&carried[point * carriedPerPoint], carriedPerPoint, own + 1);
  }
  return fields;
}

/// What the sweeps exchange on a split mesh: each point's values, shared after a sweep, and the
/// memory one process could not have, agreed at the next share so that every process stops
/// there alike. On a whole mesh nothing is shared and memory throws at once.
class SweepExchange
{
public:
  SweepExchange(const SplitVertices* split, std::size_t fields)
    : split_(split)
    , fields_(fields)
  {
  }

  void attempt(const std::function<void()>& allocate)
  {
    try
    {
      allocate();
    }
    catch (const std::bad_alloc&)
    {
      if (!split_)
      {
        throw;
      }
      ready_ = false;
    }
  }

  void share(std::vector<Rgb>& values) const
  {
    if (split_)
    {
      split_->share(values, fields_, ready_);
    }
  }

  /// After the last share: this process's failure, which its caller agrees on with the others.
  void throwIfShort() const
  {
    if (!ready_)
    {
      throw std::bad_alloc();
    }
  }

private:
  const SplitVertices* split_;
  std::size_t fields_;
  bool ready_ = true;
};
}

void serialLoop(std::size_t count, const std::function<void(std::size_t, std::size_t)>& body)
{
  body(0, count);
}

BounceGather::BounceGather(const OccluderMesh& occluders, std::vector<Rgb> directRadiosity, const Sampling& sampling,
  const std::vector<Rgb>& transferRadiosity, ShadedSides sides)
  : occluders_(occluders)
  , vertices_(directRadiosity.size() / (sides == ShadedSides::Both ? 2 : 1))
  , fields_(1 + (directRadiosity.empty() ? 0 : transferRadiosity.size() / directRadiosity.size()))
  , direct_(directOfEveryField(std::move(directRadiosity), transferRadiosity))
  , sampling_(sampling)
  , kept_(quarterOfGatherRays(sampling))
  , firstBounce_(direct_.size())
  , firstBounceError_(direct_.size() / fields_)
  , keptHits_(firstBounceError_.size() * kept_.size())
{
  if (sampling.samples < 2)
  {
    throw std::invalid_argument("BounceGather: a vertex needs at least 2 rays");
  }
  if (sides == ShadedSides::Both && firstBounceError_.size() % 2 != 0)
  {
    throw std::invalid_argument("BounceGather: both sides need each vertex's front and back");
  }
  if (occluders.triangleCount() > KeptHit::backBit - 1) // a kept hit's side is its index's top bit
  {
    throw std::invalid_argument("BounceGather: at most 2^31 - 1 triangles");
  }
}

void BounceGather::addVertex(std::size_t point, const OccluderMesh::RayHit* hits)
{
  Rgb error;
  meanOverHits(
    occluders_, std::size_t(sampling_.samples), direct_.data(), fields_, vertices_, sampling_.stratified,
    [&](std::size_t j) { return hits[j]; }, &firstBounce_[point * fields_], &error);
  firstBounceError_[point] = glm::vec3(error);
  for (std::size_t k = 0; k < kept_.size(); ++k)
  {
    keptHits_[point * kept_.size() + k] = KeptHit::of(hits[kept_[k]]);
  }
}

void BounceGather::gatherLater(const Rgb* radiosity, std::size_t first, std::size_t last, const Gathering& at,
  Rgb* irradiance, Rgb* standardError) const
{
  for (std::size_t i = first; i < last; ++i)
  {
    const std::size_t point = at.point(i);
    const KeptHit* hits = &keptHits_[point * kept_.size()];
    meanOverHits(
      occluders_, kept_.size(), radiosity, fields_, vertices_, sampling_.stratified,
      [&](std::size_t k) { return hits[k].unpacked(); }, &irradiance[point * fields_],
      standardError ? &standardError[point] : nullptr);
  }
}

std::vector<Rgb> BounceGather::lightField(const std::vector<Rgb>& values) const
{
  std::vector<Rgb> light(values.size() / fields_);
  for (std::size_t point = 0; point < light.size(); ++point)
  {
    light[point] = values[point * fields_];
  }
  return light;
}

IndirectIrradiance BounceGather::bounce(
  const Albedo& albedo, const BounceLimit& limit, bool keepBounces, const RangeLoop& loop, const SplitVertices* split)
{
  if (limit.most < 1 || firstBounce_.empty())
  {
    throw std::invalid_argument("BounceGather::bounce: at least 1 bounce, once");
  }
  const std::size_t n = firstBounceError_.size();
  const double rho = largestAlbedo(albedo, vertices_);
  if (limit.restShare > 0 && !(rho < 1))
  {
    throw std::invalid_argument("an albedo up to " + withDigits(rho, 3) +
      " reflects all the light it receives: no number of bounces bounds what the rest add");
  }
  std::vector<Rgb>().swap(direct_); // the first bounce is gathered: its room is free
  const Gathering at{ split, n };
  SweepExchange exchange(split, fields_);
  // Every field's E_1 + ... + E_k, and the light's standard error.
  std::vector<Rgb> irradiance = std::move(firstBounce_);
  IndirectIrradiance result;
  // B_k, B_1 + ... + B_{k-1}, E_k, every field's (E_1 is in irradiance, until the rest is added).
  std::vector<Rgb> radiosity, sum, gathered;
  exchange.attempt(
    [&]
    {
      // In float64 from here, in the direct radiosity's room.
      result.standardError.resize(n);
      std::copy(firstBounceError_.begin(), firstBounceError_.end(), result.standardError.begin());
      std::vector<glm::vec3>().swap(firstBounceError_);
      for (std::vector<Rgb>* made : { &radiosity, &sum, &gathered })
      {
        made->resize(n * fields_);
      }
      result.bounces.reserve(keepBounces ? std::size_t(limit.most) : 0);
    });
  exchange.share(irradiance);
  if (keepBounces)
  {
    exchange.attempt([&] { result.bounces.push_back(lightField(irradiance)); });
  }
  int bounce = 1;
  result.restBound = reflect(albedo, rho, irradiance, radiosity, loop);
  // Sweep k gathers E_k from B_{k-1} and makes B_k, whose largest value bounds the rest.
  while (bounce < limit.most && !(limit.restShare > 0 && result.restBound <= limit.restShare))
  {
    sweep(radiosity, sum, gathered, loop, at);
    exchange.share(gathered);
    ++bounce;
    if (keepBounces)
    {
      exchange.attempt([&] { result.bounces.push_back(lightField(gathered)); });
    }
    result.restBound = reflect(albedo, rho, gathered, radiosity, loop);
  }
  exchange.throwIfShort();
  result.bounceCount = bounce;
  if (bounce > 1)
  {
    addLaterBounces(sum, radiosity, gathered, irradiance, result.standardError, loop, at);
  }
  for (std::vector<Rgb>* freed : { &radiosity, &sum, &gathered })
  {
    std::vector<Rgb>().swap(*freed);
  }
  splitFields(std::move(irradiance), result);
  return result;
}

double BounceGather::reflect(const Albedo& albedo, double rho, const std::vector<Rgb>& irradiance,
  std::vector<Rgb>& radiosity, const RangeLoop& loop) const
{
  std::mutex largestLock;
  double largest = 0;
  loop(radiosity.size() / fields_,
    [&](std::size_t first, std::size_t last)
    {
      double mine = 0;
      for (std::size_t point = first; point < last; ++point)
      {
        const Rgb kd = albedoAt(albedo, point);
        for (std::size_t i = point * fields_; i < (point + 1) * fields_; ++i)
        {
          radiosity[i] = kd * irradiance[i];
        }
        mine = std::max(mine, largestComponent(radiosity[point * fields_]));
      }
      const std::lock_guard<std::mutex> lock(largestLock);
      largest = std::max(largest, mine);
    });
  return rho < 1 ? largest * rho / (1 - rho) : std::numeric_limits<double>::infinity();
}

void BounceGather::sweep(const std::vector<Rgb>& radiosity, std::vector<Rgb>& sum, std::vector<Rgb>& gathered,
  const RangeLoop& loop, const Gathering& at) const
{
  loop(radiosity.size() / fields_,
    [&](std::size_t first, std::size_t last)
    {
      for (std::size_t i = first * fields_; i < last * fields_; ++i)
      {
        sum[i] += radiosity[i];
      }
    });
  loop(at.count(),
    [&](std::size_t first, std::size_t last) { gatherLater(radiosity.data(), first, last, at, gathered.data()); });
}

void BounceGather::addLaterBounces(const std::vector<Rgb>& sum, std::vector<Rgb>& rest, std::vector<Rgb>& restError,
  std::vector<Rgb>& irradiance, std::vector<Rgb>& standardError, const RangeLoop& loop, const Gathering& at) const
{
  loop(at.count(),
    [&](std::size_t first, std::size_t last)
    {
      gatherLater(sum.data(), first, last, at, rest.data(), restError.data());
      for (std::size_t i = first; i < last; ++i)
      {
        const std::size_t point = at.point(i);
        for (std::size_t field = point * fields_; field < (point + 1) * fields_; ++field)
        {
          irradiance[field] += rest[field];
        }
        standardError[point] += restError[point];
      }
    });
}

void BounceGather::splitFields(std::vector<Rgb> irradiance, IndirectIrradiance& result) const
{
  if (fields_ == 1)
  {
    result.irradiance = std::move(irradiance);
    return;
  }
  result.irradiance = lightField(irradiance);
  const std::size_t carried = fields_ - 1;
  result.transfer.resize(result.irradiance.size() * carried);
  for (std::size_t point = 0; point < result.irradiance.size(); ++point)
  {
    std::copy_n(&irradiance[point * fields_ + 1], carried, &result.transfer[point * carried]);
  }
}
}
