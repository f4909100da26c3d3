#pragma once
// Diffuse interreflection per vertex (docs/formulas.md section 23): the irradiance that reaches
// a vertex after the light has reflected 1 .. K times off the mesh's own Lambertian surfaces.
//
// Each vertex gathers along cosine-weighted rays (gatherHits): with density cos / pi, the
// irradiance from surfaces of outgoing radiance B / pi is the mean of B over the rays' hits,
// B interpolated from the hit triangle's corners with the hit's barycentric coordinates. B is
// the radiosity: at bounce 0 the direct diffuse term kd E, and after each bounce kd times the
// irradiance it gathered. The first bounce is gathered from every ray as the rays are traced;
// the later ones, which carry kd^k less light, from a quarter of them spread over the
// hemisphere (quarterOfGatherRays), whose hits are kept: each sweep over the vertices
// (Jacobi's) adds one bounce on the same hits.
#include "OccluderMesh.h"
#include "SampleSequence.h"
#include "Vec3.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
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

/// What reaches each vertex from the mesh: the irradiance over bounces 1 .. K with its standard
/// error per channel, and each bounce's own where asked for.
struct IndirectIrradiance
{
  std::vector<Rgb> irradiance;
  std::vector<Rgb> standardError;
  std::vector<std::vector<Rgb>> bounces; // bounces[n - 1]: what bounce n adds, E_n
  int bounceCount = 0;                   // K
  /// The most that the bounces past K add to a diffuse term (BounceLimit); infinite where the
  /// albedo reaches 1.
  double restBound = 0;
};

/// How many bounces BounceGather::bounce computes: `most`, or with a restShare above 0 the
/// fewest (at most `most`) after which what the rest can add to a diffuse term is within it.
/// That is at most max(B_K) rho / (1 - rho): each bounce's radiosity is at most rho times the
/// largest of the one before it, rho the largest albedo (docs/formulas.md section 23.5).
struct BounceLimit
{
  BounceLimit(int most, double restShare = 0)
    : most(most)
    , restShare(restShare)
  {
  }
  int most;
  double restShare;
};

/// Runs body(first, last) over [0, count) in ranges, in any order and on any threads: every
/// vertex's value depends only on values of the previous sweep, so the results are the same
/// bits however it splits the range.
using RangeLoop = std::function<void(std::size_t count, const std::function<void(std::size_t, std::size_t)>& body)>;

/// The range loop of one thread.
void serialLoop(std::size_t count, const std::function<void(std::size_t, std::size_t)>& body);

/// Interreflection over the vertices of a mesh: addVertex for each vertex's traced rays, then
/// bounce().
class BounceGather
{
public:
  /// sampling.samples rays per vertex (gatherHits), from the direct radiosity B_0 (per vertex,
  /// the direct diffuse term kd E). A surface sends out no negative light: a channel of B_0
  /// below 0 (the ringing of a map's spherical-harmonic irradiance) reflects nothing.
  BounceGather(const OccluderMesh& occluders, std::vector<Rgb> directRadiosity, const Sampling& sampling);

  /// How many of a vertex's rays the later bounces gather on (quarterOfGatherRays): their hits,
  /// 8 bytes each, are most of what interreflection holds in memory.
  int laterRays() const { return int(kept_.size()); }

  /// The first bounce at `vertex` from all its rays' hits (sampling.samples of them),
  /// and the hits the later bounces use kept. Calls for different vertices may run at once.
  void addVertex(std::size_t vertex, const OccluderMesh::RayHit* hits);

  /// After addVertex for every vertex, once (it hands over the first bounce's values and frees
  /// the direct radiosity): E_1 + ... + E_K, K as `limit` says. E_n = gather(B_{n-1}) and
  /// B_n = kd E_n; E_2 + ... + E_K is gathered once more from B_1 + ... + B_{K-1} (the gather
  /// is linear in B), so that its standard error is that of one mean over the rays; the total's
  /// is the first bounce's plus the rest's (added as if they erred together: they share rays).
  /// keepBounces: also each E_n. Throws std::invalid_argument for a restShare with an albedo
  /// that reaches 1, where no number of bounces has a bound.
  IndirectIrradiance bounce(
    const Albedo& albedo, const BounceLimit& limit, bool keepBounces, const RangeLoop& loop = serialLoop);

private:
  /// E_2 + ... + E_K gathered from sum = B_1 + ... + B_{K-1} into `rest`, its standard error
  /// into `restError`, and both added to the result's.
  void addLaterBounces(const std::vector<Rgb>& sum, std::vector<Rgb>& rest, std::vector<Rgb>& restError,
    IndirectIrradiance& result, const RangeLoop& loop) const;

  /// E = gather(radiosity) on the kept hits at vertices [first, last), with the standard error
  /// where standardError is not null.
  void gatherLater(
    const Rgb* radiosity, std::size_t first, std::size_t last, Rgb* irradiance, Rgb* standardError = nullptr) const;

  /// A kept hit in 8 bytes: its triangle, and its barycentric coordinates in steps of 1/65535
  /// (an interpolation error below 1e-5 of the radiosity's spread over the triangle, far below
  /// the gather's noise), which make the later bounces' hits two thirds of what they were.
  struct KeptHit
  {
    std::uint32_t triangle;
    std::uint16_t u, v;

    static KeptHit of(const OccluderMesh::RayHit& hit)
    {
      auto step = [](float x) { return std::uint16_t(std::lround(std::clamp(double(x), 0.0, 1.0) * 65535)); };
      return { hit.triangle, step(hit.u), step(hit.v) };
    }
    OccluderMesh::RayHit unpacked() const { return { triangle, float(u / 65535.0), float(v / 65535.0) }; }
  };

  const OccluderMesh& occluders_;
  std::vector<Rgb> direct_; // B_0, at least 0
  Sampling sampling_;
  std::vector<int> kept_; // which of a vertex's rays the later bounces use
  std::vector<Rgb> firstBounce_, firstBounceError_;
  std::vector<KeptHit> keptHits_; // kept_.size() per vertex
};
}
