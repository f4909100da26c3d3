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
/// Sets of indices, joined under their lowest so that the result does not depend on the
/// order of the joins.
class DisjointSets
{
public:
  explicit DisjointSets(std::size_t count)
    : parent_(count)
  {
    std::iota(parent_.begin(), parent_.end(), std::size_t(0));
  }

  std::size_t root(std::size_t member)
  {
    while (parent_[member] != member)
    {
      member = parent_[member] = parent_[parent_[member]]; // path halving keeps the trees flat
    }
    return member;
  }

  void join(std::size_t a, std::size_t b)
  {
    const std::size_t ra = root(a), rb = root(b);
    parent_[std::max(ra, rb)] = std::min(ra, rb);
  }

private:
  std::vector<std::size_t> parent_;
};
}

PolygonEdges::PolygonEdges(const PolygonList& polygons, const std::vector<PointId>& mergeMap)
  : polygons_(polygons)
{
  if (polygons.count > std::numeric_limits<std::uint32_t>::max())
  {
    throw std::length_error("more than 2^32 polygons");
  }
  auto welded = [&](PointId id) { return mergeMap.empty() ? id : mergeMap[static_cast<std::size_t>(id)]; };
  for (std::size_t k = 0; k < polygons.count; ++k)
  {
    const std::size_t size = polygons.size(k);
    const PointId* ids = polygons.ids(k);
    for (std::size_t i = 0; size >= 3 && i < size; ++i)
    {
      const PointId from = welded(ids[i]), to = welded(ids[i + 1 < size ? i + 1 : 0]);
      if (from != to)
      {
        entries_.push_back({ std::min(from, to), 2 * std::max(from, to) + (from < to ? 1 : 0),
          static_cast<std::uint32_t>(k), static_cast<std::uint32_t>(i) });
      }
    }
  }
  std::sort(entries_.begin(), entries_.end());
}

std::size_t PolygonEdges::inconsistentCount() const
{
  std::size_t inconsistent = 0;
  for (std::size_t e = 1; e < entries_.size(); ++e)
  {
    // The same edge in the same direction twice, counted once however many repeat it.
    const bool repeatsFirstTime =
      entries_[e].sameTraversal(entries_[e - 1]) && !(e >= 2 && entries_[e].sameTraversal(entries_[e - 2]));
    inconsistent += repeatsFirstTime ? 1 : 0;
  }
  return inconsistent;
}

std::vector<PointId> unbalancedPoints(const CornerSumArray& sums, std::size_t first, std::size_t last)
{
  std::vector<PointId> points;
  for (std::size_t i = first; i < last; ++i)
  {
    if (sums[i].edgeBalance != 0)
    {
      points.push_back(static_cast<PointId>(i));
    }
  }
  return points;
}

PolygonSubset::PolygonSubset(const PolygonList& polygons, const std::vector<std::size_t>& chosen)
  : original_(chosen)
{
  for (std::size_t k : chosen)
  {
    connectivity_.insert(connectivity_.end(), polygons.ids(k), polygons.ids(k) + polygons.size(k));
    offsets_.push_back(static_cast<PointId>(connectivity_.size()));
  }
  list_ = { offsets_.data(), connectivity_.data(), offsets_.size() - 1 };
}

glm::dvec3 unitNormal(const glm::dvec3& sum)
{
  // A point with no area, or with coordinates so large that its sum overflowed, has no
  // normal; shading flags (0, 0, 0) as degenerate.
  return isFinite(sum) && largestComponent(sum) > 0.0 ? unitVector(sum) : glm::dvec3(0.0);
}

void weldCopies(CornerSumArray& sums, const PolygonEdges& edges, const std::vector<glm::dvec3>& edgePolygonAreas,
  const std::vector<PointId>& mergeMap, double featureAngleDegrees, WeldSummary* summary)
{
  // The points whose position other points share, in ascending order: the only ones that can
  // be joined.
  std::vector<PointId> shared;
  for (std::size_t i = 0; i < mergeMap.size(); ++i)
  {
    if (mergeMap[i] != static_cast<PointId>(i))
    {
      shared.insert(shared.end(), { static_cast<PointId>(i), mergeMap[i] });
    }
  }
  std::sort(shared.begin(), shared.end());
  shared.erase(std::unique(shared.begin(), shared.end()), shared.end());
  auto indexOf = [&](PointId id)
  { return static_cast<std::size_t>(std::lower_bound(shared.begin(), shared.end(), id) - shared.begin()); };

  const double cosFeatureAngle = std::cos(featureAngleDegrees * (M_PI / 180.0));
  DisjointSets copies(shared.size());
  if (!shared.empty())
  {
    edges.forEachPairOfUses(
      [&](const PolygonEdges::Use& a, const PolygonEdges::Use& b)
      {
        const glm::dvec3& areaA = edgePolygonAreas[a.polygon];
        const glm::dvec3& areaB = edgePolygonAreas[b.polygon];
        const double lengths = vectorLength(areaA) * vectorLength(areaB);
        if (lengths > 0.0 && glm::dot(areaA, areaB) >= cosFeatureAngle * lengths)
        {
          // The ends at one position are one point, or copies (and so shared).
          if (a.lowEnd != b.lowEnd)
          {
            copies.join(indexOf(a.lowEnd), indexOf(b.lowEnd));
          }
          if (a.highEnd != b.highEnd)
          {
            copies.join(indexOf(a.highEnd), indexOf(b.highEnd));
          }
        }
      });
  }
  // Joined copies' sums, added in id order so that the result is the same on any thread count.
  std::vector<glm::dvec3> joinedSums(shared.size(), glm::dvec3(0.0));
  std::vector<std::size_t> joinedCount(shared.size(), 0);
  for (std::size_t j = 0; j < shared.size(); ++j)
  {
    const std::size_t root = copies.root(j);
    joinedSums[root] += sums[static_cast<std::size_t>(shared[j])].area;
    ++joinedCount[root];
  }
  for (std::size_t j = 0; j < shared.size(); ++j)
  {
    const std::size_t root = copies.root(j);
    sums[static_cast<std::size_t>(shared[j])].area = joinedSums[root];
    if (summary)
    {
      (joinedCount[root] > 1 ? summary->pointsAveraged : summary->pointsKeptApart) += 1;
    }
  }
  if (summary)
  {
    std::vector<PointId> positions;
    for (PointId id : shared)
    {
      positions.push_back(mergeMap[static_cast<std::size_t>(id)]);
    }
    std::sort(positions.begin(), positions.end());
    summary->sharedPositions =
      static_cast<std::size_t>(std::unique(positions.begin(), positions.end()) - positions.begin());
  }
}
}
