#pragma once
// Diffuse interreflection per vertex (docs/formulas.md section 23): the irradiance that reaches
// a vertex after the light has reflected 1 .. K times off the mesh's own Lambertian surfaces.
//
// Each vertex gathers along cosine-weighted rays (gatherHits): with density cos / pi, the
// irradiance from surfaces of outgoing radiance B / pi is the mean of B over the rays' hits,
// B interpolated from the hit triangle's corners with the hit's barycentric coordinates. B is
// the radiosity: at bounce 0 the direct diffuse term kd E, and after each bounce kd times the
// irradiance it gathered, so each sweep over the vertices (Jacobi's) adds one bounce, on the
// same hits.
#include "OccluderMesh.h"
#include "Vec3.h"

#include <cstddef>
#include <functional>
#include <vector>

namespace shadelab
{
/// The albedo kd at each vertex, per channel: one for every vertex, or one per vertex.
struct Albedo
{
  Rgb uniform{ 0.0 };
  const double* perVertex = nullptr; // r, g, b per vertex; nullptr: uniform everywhere

  Rgb at(std::size_t vertex) const
  {
    return perVertex ? Rgb(perVertex[3 * vertex], perVertex[3 * vertex + 1], perVertex[3 * vertex + 2]) : uniform;
  }
};

/// Every vertex's gather: raysPerVertex first hits each (gatherHits), vertex after vertex, on
/// the triangles of occluders; stratified as the rays were drawn (the standard error pairs
/// consecutive rays, MonteCarloEstimate.h).
struct GatherTable
{
  const OccluderMesh* occluders = nullptr;
  std::size_t vertexCount = 0;
  int raysPerVertex = 0;
  const OccluderMesh::RayHit* hits = nullptr;
  bool stratified = true;
};

/// What reaches each vertex from the mesh: the irradiance over bounces 1 .. K with its standard
/// error per channel, and each bounce's own where asked for.
struct IndirectIrradiance
{
  std::vector<Rgb> irradiance;
  std::vector<Rgb> standardError;
  std::vector<std::vector<Rgb>> bounces; // bounces[n - 1]: what bounce n adds, E_n
};

/// Runs body(first, last) over [0, count) in ranges, in any order and on any threads: every
/// vertex's value depends only on values of the previous sweep, so the results are the same
/// bits however it splits the range.
using RangeLoop = std::function<void(std::size_t count, const std::function<void(std::size_t, std::size_t)>& body)>;

/// The range loop of one thread.
void serialLoop(std::size_t count, const std::function<void(std::size_t, std::size_t)>& body);

/// Irradiance at each vertex of [first, last) gathered from `radiosity` (per vertex, B): the
/// mean over its rays of B interpolated at each hit (0 for a ray that meets nothing, or the
/// back of a triangle), and, where standardError is not null, that mean's standard error.
void gatherIrradiance(const GatherTable& gather, const Rgb* radiosity, std::size_t first, std::size_t last,
  Rgb* irradiance, Rgb* standardError = nullptr);

/// K = bounces sweeps from the direct radiosity B_0 (per vertex, the direct diffuse term kd E,
/// each channel at least 0):
/// E_n = gather(B_{n-1}), B_n = kd E_n. The irradiance E_1 + ... + E_K is gathered once more
/// from B_0 + ... + B_{K-1} (the gather is linear in B), so that its standard error is that of
/// one mean over the rays. keepBounces: also each E_n.
IndirectIrradiance interreflect(const GatherTable& gather, const std::vector<Rgb>& directRadiosity,
  const Albedo& albedo, int bounces, bool keepBounces, const RangeLoop& loop = serialLoop);
}
