#pragma once
// Smooth point normals for shading, from a mesh's polygons (docs/formulas.md section 17,
// "Point normals").
//
// Each point's normal is the sum of the vector areas of the polygons around it, normalised:
// area weighting, as vtkTriangleMeshPointNormals does. Many files store one surface point as
// several points (OBJ splits them at texture seams, STL at every triangle, exporters at
// per-face colours); normals from each copy's own polygons alone shade the mesh as facets.
// So points at one position share their normal: the copies are found by position (a merge
// map), and copies whose own normals differ by more than the feature angle stay apart, so that
// an edge the file split on purpose stays sharp. Point ids and count never change.
//
// The work is in proportion to what the mesh needs. One pass over the polygons sums the area
// vectors at each point and tests each point's edges (sumAtCorners): where every edge at a point
// is traversed once in each direction, the surface closes consistently around it, and there is
// nothing to weld or to reorder. Only the other points (boundaries, seams, inconsistent or
// non-manifold edges: usually a small part of a mesh) go through the exact edge analysis.
#include "LargeMemory.h"
#include "NormalOrientation.h"
#include "Vec3.h"

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <vector>

namespace shadelab
{
/// A point id: the type of VTK's vtkIdType in its 64-bit builds (Debian's among them), so that
/// the VTK filter hands its cell arrays and merge maps over without a copy.
using PointId = long long;

/// What welding coincident points did, for the user's report.
struct WeldSummary
{
  std::size_t sharedPositions = 0; // positions held by two or more points
  std::size_t pointsAveraged = 0;  // points whose normal was averaged with a copy's
  std::size_t pointsKeptApart = 0; // copies left with their own normal by the feature angle
};

/// Polygons as VTK 9 stores them: polygon k has the ids connectivity[offsets[k]] up to
/// connectivity[offsets[k + 1]], wound anticlockwise around its front.
struct PolygonList
{
  const PointId* offsets = nullptr; // count + 1 entries
  const PointId* connectivity = nullptr;
  std::size_t count = 0;

  std::size_t size(std::size_t k) const { return static_cast<std::size_t>(offsets[k + 1] - offsets[k]); }
  const PointId* ids(std::size_t k) const { return connectivity + offsets[k]; }
};

/// A polygon's vector area: the Newell normal, half the sum of a fan's cross products, exact
/// for any planar polygon. pointAt(id) gives a point as a glm::dvec3. Polygons with fewer than
/// 3 corners have none, (0, 0, 0).
template<typename PointAt>
glm::dvec3 polygonAreaVector(const PointId* ids, std::size_t size, PointAt pointAt)
{
  if (size < 3)
  {
    return glm::dvec3(0.0);
  }
  const glm::dvec3 first = pointAt(ids[0]);
  glm::dvec3 twiceArea(0.0);
  glm::dvec3 previous = pointAt(ids[1]) - first;
  for (std::size_t i = 2; i < size; ++i)
  {
    const glm::dvec3 next = pointAt(ids[i]) - first;
    twiceArea += glm::cross(previous, next);
    previous = next;
  }
  return 0.5 * twiceArea;
}

/// Polygon k's vector area, turned round where flipped[k] is set (flipped may be empty).
template<typename PointAt>
glm::dvec3 orientedAreaVector(
  const PolygonList& polygons, std::size_t k, const std::vector<bool>& flipped, PointAt pointAt)
{
  const glm::dvec3 area = polygonAreaVector(polygons.ids(k), polygons.size(k), pointAt);
  return !flipped.empty() && flipped[k] ? -area : area;
}

/// Each polygon's vector area, turned round where flipped[k] is set (flipped may be empty).
template<typename PointAt>
std::vector<glm::dvec3> polygonAreaVectors(
  const PolygonList& polygons, const std::vector<bool>& flipped, PointAt pointAt)
{
  std::vector<glm::dvec3> areas(polygons.count);
  for (std::size_t k = 0; k < polygons.count; ++k)
  {
    areas[k] = orientedAreaVector(polygons, k, flipped, pointAt);
  }
  return areas;
}

/// A pseudo-random 64-bit signature of a point id (the SplitMix64 finaliser: S. Vigna,
/// https://prng.di.unimi.it/splitmix64.c), for the edge balance.
inline std::uint64_t idSignature(PointId id)
{
  std::uint64_t z = static_cast<std::uint64_t>(id) + 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

/// Points stored as x, y, z values one after another (VTK's array layout, and glm::dvec3's),
/// read as glm::dvec3.
template<typename Real>
struct PackedPoints
{
  const Real* xyz;

  glm::dvec3 operator()(PointId id) const
  {
    const Real* p = xyz + 3 * id;
    return glm::dvec3(p[0], p[1], p[2]);
  }
  void prefetch(PointId id) const { __builtin_prefetch(xyz + 3 * id, 0); }
};

/// What a pass over the polygons gathers at one point, in 32 bytes: half a cache line, which
/// each corner of each polygon updates once.
struct CornerSum
{
  /// The sum of the vector areas of the polygons around the point.
  glm::dvec3 area{ 0.0 };
  /// The sum, modulo 2^64, of idSignature(next) - idSignature(previous) over the point's
  /// corners. Each edge p -> q adds signature(q) at p's corner and each edge q -> p subtracts
  /// it, so the sum is 0 where every edge at p is traversed once in each direction (a surface
  /// closing around p, consistently wound) and, but for a chance of about 2^-64, not 0 where
  /// an edge is used once (a boundary or seam), or twice in one direction (inconsistent
  /// winding).
  std::uint64_t edgeBalance = 0;
};

using CornerSumArray = std::vector<CornerSum, LargeAllocator<CornerSum>>; // in huge pages: no page fault per 4 kB

/// What a pass over the polygons gathers at each point, and about the mesh.
struct CornerSums
{
  /// Zero sums for pointCount points; the winding's orientation is taken about centre, for a
  /// mesh within radius of it.
  CornerSums(std::size_t pointCount, const glm::dvec3& centre, double radius)
    : points(pointCount)
    , winding(centre, radius)
  {
  }

  CornerSumArray points;
  /// Whether the polygons' own winding points out of the mesh: each polygon counts with its
  /// vector area at the mean of its corners (exact for planar polygons, whose vector area is
  /// normal to their plane).
  NormalOrientationAccumulator winding;
};

/// A point's signature in the edge balance (CornerSum): that of its id.
struct IdSignature
{
  std::uint64_t operator()(PointId id) const { return idSignature(id); }
};

/// A corner watch that watches nothing (sumAtCorners' default).
struct NoCornerWatch
{
  void operator()(std::size_t, PointId, std::uint64_t, const glm::dvec3&) const {}
};

/// Adds polygons first..last-1 (turned round where flipped[k] is set; flipped may be empty)
/// to sums; signatureOf(id) is the edge balance's signature of the point `id` (its id's, or in a
/// piece of a split mesh its global id's). watch(k, id, balance, area) is told, at each corner,
/// what polygon k adds at the point `id`: what a piece of a split mesh sends the pieces that
/// share the point.
///
/// The pass is bound by memory: each corner updates a point's sums, which are seldom in cache,
/// and reads a point, which seldom is either. So both are fetched some polygons ahead of their
/// use (16: 2 to 16 were tried, on 2.2M vertices; 16 took 13% less time than 2), and nothing
/// here divides (a division's latency showed as much as the misses).
template<typename Real, typename Signature = IdSignature, typename CornerWatch = NoCornerWatch>
void sumAtCorners(const PolygonList& polygons, std::size_t first, std::size_t last, const std::vector<bool>& flipped,
  PackedPoints<Real> points, CornerSums& sums, Signature signatureOf = {}, CornerWatch watch = {})
{
  constexpr std::size_t lookAhead = 16;
  for (std::size_t k = first; k < last; ++k)
  {
    if (k + lookAhead < last)
    {
      const PointId* ahead = polygons.ids(k + lookAhead);
      for (std::size_t i = 0; i < polygons.size(k + lookAhead); ++i)
      {
        points.prefetch(ahead[i]);
        __builtin_prefetch(&sums.points[static_cast<std::size_t>(ahead[i])], 1);
      }
    }
    const std::size_t size = polygons.size(k);
    const PointId* ids = polygons.ids(k);
    if (size < 3)
    {
      continue;
    }
    const glm::dvec3 area = orientedAreaVector(polygons, k, flipped, points);
    // Walks the corners with the previous and next ids at hand (no modulo).
    std::uint64_t previous = signatureOf(ids[size - 1]), current = signatureOf(ids[0]);
    glm::dvec3 cornerSum(0.0);
    for (std::size_t i = 0; i < size; ++i)
    {
      const std::uint64_t next = signatureOf(ids[i + 1 < size ? i + 1 : 0]);
      CornerSum& sum = sums.points[static_cast<std::size_t>(ids[i])];
      sum.area += area;
      sum.edgeBalance += next - previous;
      watch(k, ids[i], next - previous, area);
      previous = current;
      current = next;
      cornerSum += points(ids[i]);
    }
    const double inverseSize = size == 3 ? 1.0 / 3.0 : 1.0 / static_cast<double>(size);
    sums.winding.add(area, glm::length(area), cornerSum * inverseSize);
  }
}

/// The points among first..last-1 whose edgeBalance is not 0, in ascending order: the only
/// ones that can be on a seam, a boundary or an inconsistently wound edge.
std::vector<PointId> unbalancedPoints(const CornerSumArray& sums, std::size_t first, std::size_t last);

/// Whether polygon k has an edge between two points for which listed[id] is set. Every
/// corner is looked at, with no branch on what it finds: on a whole mesh, branches on listed
/// points cost more in mispredictions than the few extra loads.
inline bool hasEdgeBetween(const PolygonList& polygons, std::size_t k, const std::vector<std::uint8_t>& listed)
{
  const std::size_t size = polygons.size(k);
  const PointId* ids = polygons.ids(k);
  std::uint8_t previousListed = size > 0 ? listed[static_cast<std::size_t>(ids[size - 1])] : 0;
  std::uint8_t found = 0;
  for (std::size_t i = 0; i < size; ++i)
  {
    const std::uint8_t listedHere = listed[static_cast<std::size_t>(ids[i])];
    found |= previousListed & listedHere;
    previousListed = listedHere;
  }
  return found != 0;
}

/// Some of a list's polygons (those with an edge between unbalanced points, say), as a list of
/// their own.
class PolygonSubset
{
public:
  /// The polygons whose indices `chosen` holds, in its order.
  PolygonSubset(const PolygonList& polygons, const std::vector<std::size_t>& chosen);

  const PolygonList& list() const { return list_; }
  /// The index, in the whole list, of the subset's polygon k.
  std::size_t original(std::size_t k) const { return original_[k]; }

private:
  std::vector<PointId> offsets_{ 0 };
  std::vector<PointId> connectivity_;
  std::vector<std::size_t> original_;
  PolygonList list_;
};

/// For the given points (ascending), the map of those that share exact coordinates with a
/// lower one to the lowest such id (mergeMap[i] = i for every other point), or an empty map
/// when no two of them share a position. pointAt(id) gives a point as a glm::dvec3; points
/// with a non-finite coordinate share with none.
template<typename PointAt>
std::vector<PointId> coincidentPointMap(const std::vector<PointId>& points, std::size_t pointCount, PointAt pointAt);

/// Every edge of the polygons between welded ids (mergeMap[i] is the id of the point that
/// stands for point i's position; empty: no welding), grouped by edge, so that polygons that
/// meet at an edge can be found, even where the file stores the edge's points twice.
class PolygonEdges
{
public:
  PolygonEdges(const PolygonList& polygons, const std::vector<PointId>& mergeMap);

  /// The number of edges that two polygons traverse in the same direction. Neighbours on a
  /// consistently wound surface traverse their shared edge in opposite directions, so 0
  /// means the winding is consistent and the normals all point to one side.
  std::size_t inconsistentCount() const;

  /// One polygon's use of an edge: the edge's ends as the polygon stores them (not welded).
  struct Use
  {
    std::size_t polygon;
    PointId lowEnd, highEnd; // the points at the welded edge's lower and higher welded id
  };

  /// Calls visit(a, b) for every two uses of one edge by different polygons.
  template<typename Visit>
  void forEachPairOfUses(Visit&& visit) const;

private:
  /// One polygon's traversal of an edge.
  struct Entry
  {
    PointId low;           // the lower welded end
    PointId key;           // 2 x the higher welded end, + 1 if traversed from the lower end
    std::uint32_t polygon; // the polygon, and the corner its edge starts at
    std::uint32_t corner;

    bool sameEdge(const Entry& other) const { return low == other.low && key / 2 == other.key / 2; }
    bool sameTraversal(const Entry& other) const { return low == other.low && key == other.key; }
    bool operator<(const Entry& other) const
    {
      return low != other.low      ? low < other.low
        : key != other.key         ? key < other.key
        : polygon != other.polygon ? polygon < other.polygon
                                   : corner < other.corner;
    }
  };

  Use useOf(const Entry& entry) const
  {
    const PointId* ids = polygons_.ids(entry.polygon);
    const PointId from = ids[entry.corner], to = ids[(entry.corner + 1) % polygons_.size(entry.polygon)];
    const bool lowToHigh = (entry.key & 1) != 0;
    return { entry.polygon, lowToHigh ? from : to, lowToHigh ? to : from };
  }

  PolygonList polygons_;
  std::vector<Entry> entries_; // sorted, so that the entries of one edge are adjacent
};

template<typename Visit>
void PolygonEdges::forEachPairOfUses(Visit&& visit) const
{
  for (std::size_t a = 0; a < entries_.size(); ++a)
  {
    for (std::size_t b = a + 1; b < entries_.size() && entries_[b].sameEdge(entries_[a]); ++b)
    {
      if (entries_[a].polygon != entries_[b].polygon)
      {
        visit(useOf(entries_[a]), useOf(entries_[b]));
      }
    }
  }
}

/// Welding: each copy of a point (mergeMap[i] != i, or a point others map to) gets the sum
/// of the area sums of the copies it is joined to, in place (edge balances are left as they are). Two copies are joined
/// where two polygons around them meet at an edge (of `edges`, built with mergeMap; edgePolygonAreas are those
/// polygons' area vectors) at less than featureAngleDegrees, and joins chain: a seam through a smooth surface
/// disappears, and an edge the file split on purpose stays sharp.
void weldCopies(CornerSumArray& sums, const PolygonEdges& edges, const std::vector<glm::dvec3>& edgePolygonAreas,
  const std::vector<PointId>& mergeMap, double featureAngleDegrees, WeldSummary* summary = nullptr);

/// A point's unit normal from its area sum; (0, 0, 0) for a point without area (isolated, or
/// only degenerate polygons), which shading flags.
glm::dvec3 unitNormal(const glm::dvec3& areaSum);

template<typename PointAt>
std::vector<PointId> coincidentPointMap(const std::vector<PointId>& points, std::size_t pointCount, PointAt pointAt)
{
  struct Located
  {
    glm::dvec3 position;
    PointId id;
  };
  std::vector<Located> located;
  located.reserve(points.size());
  for (PointId id : points)
  {
    const glm::dvec3 p = pointAt(id);
    if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))
    {
      located.push_back({ p, id });
    }
  }
  // -0 and +0 compare equal, so they are one position, as they are one point.
  auto before = [](const Located& a, const Located& b)
  {
    if (a.position.x != b.position.x)
      return a.position.x < b.position.x;
    if (a.position.y != b.position.y)
      return a.position.y < b.position.y;
    if (a.position.z != b.position.z)
      return a.position.z < b.position.z;
    return a.id < b.id;
  };
  std::sort(located.begin(), located.end(), before);
  std::vector<PointId> map;
  for (std::size_t k = 1; k < located.size(); ++k)
  {
    if (located[k].position == located[k - 1].position)
    {
      if (map.empty())
      {
        map.resize(pointCount);
        std::iota(map.begin(), map.end(), PointId(0));
      }
      // Sorted by id within a position: the first of a run stands for all of it.
      map[static_cast<std::size_t>(located[k].id)] = map[static_cast<std::size_t>(located[k - 1].id)];
    }
  }
  return map;
}
}
