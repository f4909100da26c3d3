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
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <cstddef>
#include <cstdint>
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

/// Each polygon's vector area (the Newell normal: half the sum of a fan's cross products,
/// exact for any planar polygon), turned round where flipped[k] is set (flipped may be
/// empty). pointAt(id) gives a point as a glm::dvec3. Polygons with fewer than 3 corners have
/// none (0, 0, 0).
template <typename PointAt>
std::vector<glm::dvec3> polygonAreaVectors(const PolygonList& polygons, const std::vector<bool>& flipped, PointAt pointAt)
{
  std::vector<glm::dvec3> areas(polygons.count, glm::dvec3(0.0));
  for (std::size_t k = 0; k < polygons.count; ++k)
  {
    const std::size_t size = polygons.size(k);
    const PointId* ids = polygons.ids(k);
    if (size < 3)
    {
      continue;
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
    areas[k] = (!flipped.empty() && flipped[k] ? -0.5 : 0.5) * twiceArea;
  }
  return areas;
}

/// Every edge of the polygons between welded ids (mergeMap[i] is the id of the point that
/// stands for point i's position; empty: no welding), grouped by edge, so that polygons that
/// meet at an edge can be found, even where the file stores the edge's points twice.
class PolygonEdges
{
public:
  PolygonEdges(const PolygonList& polygons, const std::vector<PointId>& mergeMap, std::size_t pointCount);

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
  template <typename Visit>
  void forEachPairOfUses(Visit&& visit) const;

private:
  /// One polygon's traversal of an edge, in 16 bytes: a large mesh has six per triangle.
  struct Entry
  {
    PointId key;           // 2 x the higher welded end, + 1 if traversed from the lower end
    std::uint32_t polygon; // the polygon, and the corner its edge starts at
    std::uint32_t corner;
    bool operator<(const Entry& other) const
    {
      return key != other.key ? key < other.key
                              : (polygon != other.polygon ? polygon < other.polygon : corner < other.corner);
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
  std::vector<std::size_t> start_; // the entries of lower welded end v are entries_[start_[v]..start_[v+1])
  std::vector<Entry> entries_;     // sorted within each lower end
};

template <typename Visit>
void PolygonEdges::forEachPairOfUses(Visit&& visit) const
{
  for (std::size_t v = 0; v + 1 < start_.size(); ++v)
  {
    for (std::size_t a = start_[v]; a < start_[v + 1]; ++a)
    {
      // Entries of one edge are adjacent: their keys differ in the direction bit at most.
      for (std::size_t b = a + 1; b < start_[v + 1] && entries_[b].key / 2 == entries_[a].key / 2; ++b)
      {
        if (entries_[a].polygon != entries_[b].polygon)
        {
          visit(useOf(entries_[a]), useOf(entries_[b]));
        }
      }
    }
  }
}

/// Unit normals, one per point, from the polygons' area vectors: each point's is the sum over
/// the polygons around it. With welding (edges built with a merge map), copies of one point
/// share their sum where two of their polygons meet at an edge at less than
/// featureAngleDegrees (polygons joined in a chain count): a seam through a smooth surface
/// disappears, and an edge the file split on purpose stays sharp. A point without area
/// (isolated, or only degenerate polygons) gets (0, 0, 0), which shading flags.
std::vector<glm::dvec3> unitPointNormals(std::size_t pointCount, const PolygonList& polygons,
  const std::vector<glm::dvec3>& areaVectors, const PolygonEdges* weldedEdges, const std::vector<PointId>& mergeMap,
  double featureAngleDegrees, WeldSummary* summary = nullptr);
}
