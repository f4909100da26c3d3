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
//
// Transfer vectors may be carried through the same bounces (Sloan, Kautz and Snyder 2002,
// section 5, "interreflected transfer"): the gather is linear in B, so gathering each
// coefficient's radiosity kd T_k as a field of its own gives the indirect part of the transfer,
// whose dot product with any map's coefficients is the indirect irradiance under that map.
//
// A two-sided material sends light out from both sides of the surface: each vertex is then two
// points, its front (the side its normal points to) and its back, each gathering on its own
// side, and a ray that meets a triangle's back reads the backs' radiosity.
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

/// Which sides of the surface send light out and gather it: the side each vertex's normal points
/// to, or both (a two-sided material). With both, a mesh of N vertices has 2 N points: point v
/// is vertex v's front, point N + v its back.
enum class ShadedSides
{
  Front,
  Both
};

/// What reaches each point from the mesh: the irradiance over bounces 1 .. K with its standard
/// error per channel, and each bounce's own where asked for.
struct IndirectIrradiance
{
  std::vector<Rgb> irradiance;
  std::vector<Rgb> standardError;
  std::vector<std::vector<Rgb>> bounces; // bounces[n - 1]: what bounce n adds, E_n
  /// The carried fields' E_1 + ... + E_K, each point's after one another (BounceGather's
  /// transferRadiosity); empty where none was carried.
  std::vector<Rgb> transfer;
  int bounceCount = 0; // K
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

/// A mesh split over processes, each holding the whole mesh's triangles but gathering at its
/// own vertices only: the sweeps read every vertex's values, so after each one the processes
/// share what they computed. Every vertex's value is then the one process alone computes.
struct SplitVertices
{
  /// The points this process gathers at (several processes may hold one); may be empty.
  std::vector<std::size_t> own;
  /// Fills in every point's values (perVertex of them each), given this process's own
  /// points', from the processes that hold them: a collective call, which every process makes
  /// as often as the others (the bounces' count is the same everywhere). `ready` says whether
  /// this process made what it had to since the last call (its memory); where any process did
  /// not, it throws std::runtime_error on every process alike, so that none waits for another.
  std::function<void(std::vector<Rgb>& values, std::size_t perVertex, bool ready)> share;
};

/// Interreflection over the points of a mesh (its vertices, or with both sides each vertex's
/// front and back): addVertex for each point's traced rays, then bounce().
class BounceGather
{
public:
  /// sampling.samples rays per point (gatherHits, with lit backs where both sides are
  /// shaded), from the direct radiosity B_0 (per point, the direct diffuse term kd E on its
  /// side). A surface sends out no negative light: a channel of B_0 below 0 (the ringing of a
  /// map's spherical-harmonic irradiance) reflects nothing. transferRadiosity, if not empty,
  /// carries fields through the same bounces: the same count per point, each point's after one
  /// another (for a transfer vector, coefficient k's kd T_k, channel by channel). They are
  /// signed and kept so: a coefficient is not a light. The albedo is a vertex's on both its
  /// sides.
  BounceGather(const OccluderMesh& occluders, std::vector<Rgb> directRadiosity, const Sampling& sampling,
    const std::vector<Rgb>& transferRadiosity = {}, ShadedSides sides = ShadedSides::Front);

  /// How many of a point's rays the later bounces gather on (quarterOfGatherRays): their hits,
  /// 8 bytes each, are most of what interreflection holds in memory.
  int laterRays() const { return int(kept_.size()); }

  /// The first bounce at `point` from all its rays' hits (sampling.samples of them),
  /// and the hits the later bounces use kept. Calls for different points may run at once.
  void addVertex(std::size_t point, const OccluderMesh::RayHit* hits);

  /// After addVertex for every vertex, once (it hands over the first bounce's values and frees
  /// the direct radiosity): E_1 + ... + E_K, K as `limit` says, and the carried fields' over
  /// the same K bounces. E_n = gather(B_{n-1}) and
  /// B_n = kd E_n; E_2 + ... + E_K is gathered once more from B_1 + ... + B_{K-1} (the gather
  /// is linear in B), so that its standard error is that of one mean over the rays; the total's
  /// is the first bounce's plus the rest's (added as if they erred together: they share rays).
  /// keepBounces: also each E_n. Throws std::invalid_argument for a restShare with an albedo
  /// that reaches 1, where no number of bounces has a bound. With `split`, addVertex has been
  /// called for its own points only, and only theirs are computed in the result (the bounds
  /// and bounce counts are every point's, the same on every process).
  IndirectIrradiance bounce(const Albedo& albedo, const BounceLimit& limit, bool keepBounces,
    const RangeLoop& loop = serialLoop, const SplitVertices* split = nullptr);

private:
  /// The points this process gathers at: `split`'s own, or every one.
  struct Gathering
  {
    const SplitVertices* split;
    std::size_t all;
    std::size_t count() const { return split ? split->own.size() : all; }
    std::size_t point(std::size_t i) const { return split ? split->own[i] : i; }
  };

  /// The albedo at a point: its vertex's.
  Rgb albedoAt(const Albedo& albedo, std::size_t point) const { return albedo.at(point % vertices_); }

  /// B = kd E, every field at every point, into radiosity; returns the bound on what the
  /// bounces past this one add to the light (BounceLimit), rho the largest albedo.
  double reflect(const Albedo& albedo, double rho, const std::vector<Rgb>& irradiance, std::vector<Rgb>& radiosity,
    const RangeLoop& loop) const;

  /// One sweep: sum += radiosity everywhere, and gathered = gather(radiosity) at the points
  /// this process gathers at.
  void sweep(const std::vector<Rgb>& radiosity, std::vector<Rgb>& sum, std::vector<Rgb>& gathered,
    const RangeLoop& loop, const Gathering& at) const;

  /// E_2 + ... + E_K gathered from sum = B_1 + ... + B_{K-1} into `rest` (every field), the
  /// light's standard error into `restError`, and both added to irradiance and standardError.
  void addLaterBounces(const std::vector<Rgb>& sum, std::vector<Rgb>& rest, std::vector<Rgb>& restError,
    std::vector<Rgb>& irradiance, std::vector<Rgb>& standardError, const RangeLoop& loop, const Gathering& at) const;

  /// Every field's irradiance handed to the result: the light's and the carried fields'.
  void splitFields(std::vector<Rgb> irradiance, IndirectIrradiance& result) const;

  /// E = gather(radiosity) on the kept hits at the points at.point(first .. last - 1), every
  /// field (fields_ of them per point), with the light's standard error where standardError is
  /// not null.
  void gatherLater(const Rgb* radiosity, std::size_t first, std::size_t last, const Gathering& at, Rgb* irradiance,
    Rgb* standardError = nullptr) const;

  /// Field 0 of each point, the light's, out of values of every field.
  std::vector<Rgb> lightField(const std::vector<Rgb>& values) const;

  /// A kept hit in 8 bytes: its triangle with the side it met in the top bit, and its
  /// barycentric coordinates in steps of 1/65535 (an interpolation error below 1e-5 of the
  /// radiosity's spread over the triangle, far below the gather's noise), which make the later
  /// bounces' hits two thirds of what they were.
  struct KeptHit
  {
    static constexpr std::uint32_t backBit = 0x8000'0000u;
    std::uint32_t triangleAndSide;
    std::uint16_t u, v;

    static KeptHit of(const OccluderMesh::RayHit& hit)
    {
      auto step = [](float x) { return std::uint16_t(std::lround(std::clamp(double(x), 0.0, 1.0) * 65535)); };
      const bool miss = hit.triangle == OccluderMesh::RayHit::noTriangle;
      return { miss || !hit.onBack ? hit.triangle : hit.triangle | backBit, step(hit.u), step(hit.v) };
    }
    OccluderMesh::RayHit unpacked() const
    {
      const bool onBack = triangleAndSide != OccluderMesh::RayHit::noTriangle && (triangleAndSide & backBit) != 0;
      return { onBack ? triangleAndSide & ~backBit : triangleAndSide, float(u / 65535.0), float(v / 65535.0), onBack };
    }
  };

  const OccluderMesh& occluders_;
  std::size_t vertices_;    // N; the points are N, or 2 N with both sides
  std::size_t fields_;      // per point: the light's radiosity, then the carried fields
  std::vector<Rgb> direct_; // B_0 of every field; the light's at least 0
  Sampling sampling_;
  std::vector<int> kept_;        // which of a point's rays the later bounces use
  std::vector<Rgb> firstBounce_; // every field's
  /// The light's, in float32 while the rays are traced (it bounds an estimate's error and needs
  /// no more digits): 12 bytes a point less at the gather's peak of memory.
  std::vector<glm::vec3> firstBounceError_;
  std::vector<KeptHit> keptHits_; // kept_.size() per point
};
}
