#include "PointNormals.h"

#include "Vec3.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace shadelab
{
namespace
{
glm::dvec3 unitOrZero(const glm::dvec3& sum)
{
  // A point with no area, or with coordinates so large that its sum overflowed, has no
  // normal; shading flags (0, 0, 0) as degenerate.
  return isFinite(sum) && largestComponent(sum) > 0.0 ? unitVector(sum) : glm::dvec3(0.0);
}

/// Sets of points, joined under their lowest id so that the result does not depend on the
/// order of the joins.
class DisjointSets
{
public:
  explicit DisjointSets(std::size_t count)
    : parent_(count)
  {
    std::iota(parent_.begin(), parent_.end(), PointId(0));
  }

  PointId root(PointId id)
  {
    while (parent_[static_cast<std::size_t>(id)] != id)
    {
      // Path halving keeps the trees flat.
      id = parent_[static_cast<std::size_t>(id)] = parent_[static_cast<std::size_t>(parent_[static_cast<std::size_t>(id)])];
    }
    return id;
  }

  void join(PointId a, PointId b)
  {
    const PointId ra = root(a), rb = root(b);
    parent_[static_cast<std::size_t>(std::max(ra, rb))] = std::min(ra, rb);
  }

private:
  std::vector<PointId> parent_;
};
}

PolygonEdges::PolygonEdges(const PolygonList& polygons, const std::vector<PointId>& mergeMap, std::size_t pointCount)
  : polygons_(polygons)
  , start_(pointCount + 1, 0)
{
  if (polygons.count > std::numeric_limits<std::uint32_t>::max())
  {
    throw std::length_error("more than 2^32 polygons");
  }
  auto welded = [&](PointId id) { return mergeMap.empty() ? id : mergeMap[static_cast<std::size_t>(id)]; };
  // Two passes over the edges: count them by lower welded end, then file them there.
  auto forEachEdge = [&](auto&& visit)
  {
    for (std::size_t k = 0; k < polygons.count; ++k)
    {
      const std::size_t size = polygons.size(k);
      const PointId* ids = polygons.ids(k);
      for (std::size_t i = 0; size >= 3 && i < size; ++i)
      {
        const PointId from = welded(ids[i]), to = welded(ids[(i + 1) % size]);
        if (from != to)
        {
          visit(std::min(from, to),
            Entry{ 2 * std::max(from, to) + (from < to ? 1 : 0), static_cast<std::uint32_t>(k),
              static_cast<std::uint32_t>(i) });
        }
      }
    }
  };
  forEachEdge([&](PointId low, const Entry&) { ++start_[static_cast<std::size_t>(low) + 1]; });
  std::partial_sum(start_.begin(), start_.end(), start_.begin());
  entries_.resize(start_.back());
  std::vector<std::size_t> next(start_.begin(), start_.end() - 1);
  forEachEdge([&](PointId low, const Entry& entry) { entries_[next[static_cast<std::size_t>(low)]++] = entry; });
  for (std::size_t v = 0; v < pointCount; ++v)
  {
    std::sort(entries_.begin() + static_cast<std::ptrdiff_t>(start_[v]),
      entries_.begin() + static_cast<std::ptrdiff_t>(start_[v + 1]));
  }
}

std::size_t PolygonEdges::inconsistentCount() const
{
  std::size_t inconsistent = 0;
  for (std::size_t v = 0; v + 1 < start_.size(); ++v)
  {
    for (std::size_t e = start_[v] + 1; e < start_[v + 1]; ++e)
    {
      // The same edge in the same direction twice, counted once however many repeat it.
      const bool repeatsFirstTime = entries_[e].key == entries_[e - 1].key &&
        !(e >= start_[v] + 2 && entries_[e].key == entries_[e - 2].key);
      inconsistent += repeatsFirstTime ? 1 : 0;
    }
  }
  return inconsistent;
}

std::vector<glm::dvec3> unitPointNormals(std::size_t pointCount, const PolygonList& polygons,
  const std::vector<glm::dvec3>& areaVectors, const PolygonEdges* weldedEdges, const std::vector<PointId>& mergeMap,
  double featureAngleDegrees, WeldSummary* summary)
{
  // Summed in polygon order, so that the result is the same on any thread count.
  std::vector<glm::dvec3> sums(pointCount, glm::dvec3(0.0));
  for (std::size_t k = 0; k < polygons.count; ++k)
  {
    for (std::size_t i = 0; i < polygons.size(k); ++i)
    {
      sums[static_cast<std::size_t>(polygons.ids(k)[i])] += areaVectors[k];
    }
  }
  std::vector<glm::dvec3> normals(pointCount);
  if (!weldedEdges)
  {
    std::transform(sums.begin(), sums.end(), normals.begin(), unitOrZero);
    return normals;
  }
  const double cosFeatureAngle = std::cos(featureAngleDegrees * (M_PI / 180.0));
  DisjointSets copies(pointCount);
  weldedEdges->forEachPairOfUses(
    [&](const PolygonEdges::Use& a, const PolygonEdges::Use& b)
    {
      const glm::dvec3& areaA = areaVectors[a.polygon];
      const glm::dvec3& areaB = areaVectors[b.polygon];
      const double lengths = vectorLength(areaA) * vectorLength(areaB);
      if (lengths > 0.0 && glm::dot(areaA, areaB) >= cosFeatureAngle * lengths)
      {
        copies.join(a.lowEnd, b.lowEnd);
        copies.join(a.highEnd, b.highEnd);
      }
    });
  std::vector<glm::dvec3> joinedSums(pointCount, glm::dvec3(0.0));
  std::vector<std::size_t> joinedCount(pointCount, 0);
  for (std::size_t i = 0; i < pointCount; ++i)
  {
    const std::size_t root = static_cast<std::size_t>(copies.root(static_cast<PointId>(i)));
    joinedSums[root] += sums[i];
    ++joinedCount[root];
  }
  std::vector<std::size_t> pointsAtPosition(pointCount, 0);
  for (PointId position : mergeMap)
  {
    ++pointsAtPosition[static_cast<std::size_t>(position)];
  }
  for (std::size_t i = 0; i < pointCount; ++i)
  {
    const std::size_t root = static_cast<std::size_t>(copies.root(static_cast<PointId>(i)));
    normals[i] = unitOrZero(joinedSums[root]);
    if (summary && pointsAtPosition[static_cast<std::size_t>(mergeMap[i])] > 1)
    {
      (joinedCount[root] > 1 ? summary->pointsAveraged : summary->pointsKeptApart) += 1;
    }
  }
  if (summary)
  {
    summary->sharedPositions = static_cast<std::size_t>(
      std::count_if(pointsAtPosition.begin(), pointsAtPosition.end(), [](std::size_t count) { return count > 1; }));
  }
  return normals;
}
}
