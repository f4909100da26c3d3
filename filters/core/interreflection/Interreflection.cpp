#include "Interreflection.h"

#include "MonteCarloEstimate.h"

#include <algorithm>
#include <array>
#include <stdexcept>

namespace shadelab
{
namespace
{
/// B at a hit: its triangle's corners' values weighted by the hit's barycentric coordinates.
Rgb radiosityAt(const GatherTable& gather, const Rgb* radiosity, const OccluderMesh::RayHit& hit)
{
  const std::array<std::uint32_t, 3> corners = gather.occluders->corners(hit.triangle);
  const double u = hit.u, v = hit.v;
  return (1.0 - u - v) * radiosity[corners[0]] + u * radiosity[corners[1]] + v * radiosity[corners[2]];
}
}

void serialLoop(std::size_t count, const std::function<void(std::size_t, std::size_t)>& body)
{
  body(0, count);
}

void gatherIrradiance(const GatherTable& gather, const Rgb* radiosity, std::size_t first, std::size_t last,
  Rgb* irradiance, Rgb* standardError)
{
  const std::size_t rays = static_cast<std::size_t>(gather.raysPerVertex);
  for (std::size_t vertex = first; vertex < last; ++vertex)
  {
    MonteCarloEstimate mean(gather.stratified);
    const OccluderMesh::RayHit* hits = gather.hits + vertex * rays;
    for (std::size_t j = 0; j < rays; ++j)
    {
      mean.add(
        hits[j].triangle == OccluderMesh::RayHit::noTriangle ? Rgb(0.0) : radiosityAt(gather, radiosity, hits[j]));
    }
    irradiance[vertex] = mean.mean();
    if (standardError)
    {
      standardError[vertex] = rays > 1 ? mean.standardError() : Rgb(0.0);
    }
  }
}

IndirectIrradiance interreflect(const GatherTable& gather, const std::vector<Rgb>& directRadiosity,
  const Albedo& albedo, int bounces, bool keepBounces, const RangeLoop& loop)
{
  if (directRadiosity.size() != gather.vertexCount || bounces < 0)
  {
    throw std::invalid_argument("interreflect: a radiosity per vertex and a count of bounces >= 0 are needed");
  }
  const std::size_t n = gather.vertexCount;
  IndirectIrradiance result;
  result.irradiance.assign(n, Rgb(0.0));
  result.standardError.assign(n, Rgb(0.0));
  if (bounces == 0)
  {
    return result;
  }
  // A surface sends out no negative light: a direct term below 0 (the ringing of a map's
  // spherical-harmonic irradiance, docs/formulas.md section 12.5) reflects nothing.
  std::vector<Rgb> radiosity(n); // B_{n-1}
  std::transform(directRadiosity.begin(), directRadiosity.end(), radiosity.begin(),
    [](const Rgb& b) { return glm::max(b, Rgb(0.0)); });
  std::vector<Rgb> sum = radiosity; // B_0 + ... + B_{n-1}
  std::vector<Rgb> gathered(n);     // E_n
  // Sweep n gathers E_n from B_{n-1} and makes B_n for the sweeps after it. The total needs
  // B_0 .. B_{K-1} only: sweep K is made only to keep E_K apart.
  const int sweeps = keepBounces ? bounces : bounces - 1;
  for (int bounce = 1; bounce <= sweeps; ++bounce)
  {
    loop(n,
      [&](std::size_t first, std::size_t last)
      { gatherIrradiance(gather, radiosity.data(), first, last, gathered.data()); });
    if (keepBounces)
    {
      result.bounces.push_back(gathered);
    }
    if (bounce < bounces)
    {
      loop(n,
        [&](std::size_t first, std::size_t last)
        {
          for (std::size_t vertex = first; vertex < last; ++vertex)
          {
            radiosity[vertex] = albedo.at(vertex) * gathered[vertex];
            sum[vertex] += radiosity[vertex];
          }
        });
    }
  }
  loop(n,
    [&](std::size_t first, std::size_t last)
    { gatherIrradiance(gather, sum.data(), first, last, result.irradiance.data(), result.standardError.data()); });
  return result;
}
}
