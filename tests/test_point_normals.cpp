// Point normals from polygons (PointNormals.h) on meshes small enough to know every normal:
// area weighting, welding copies of a point across a seam, keeping them apart at a sharp
// edge, and the winding test.
#include "PointNormals.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <utility>

namespace
{
using namespace shadelab;

/// Triangles given as corner ids into points, in the PolygonList layout.
struct Triangles
{
  std::vector<glm::dvec3> points;
  std::vector<PointId> offsets{ 0 };
  std::vector<PointId> connectivity;

  void add(PointId a, PointId b, PointId c)
  {
    connectivity.insert(connectivity.end(), { a, b, c });
    offsets.push_back(static_cast<PointId>(connectivity.size()));
  }
  PolygonList list() const { return { offsets.data(), connectivity.data(), offsets.size() - 1 }; }
  glm::dvec3 at(PointId id) const { return points[static_cast<std::size_t>(id)]; }
  std::vector<glm::dvec3> areas() const
  {
    return polygonAreaVectors(list(), {}, [this](PointId id) { return at(id); });
  }
  CornerSums sums() const
  {
    CornerSums sums(points.size(), glm::dvec3(0.0), 2.0); // the corners are within 2 of the origin
    sumAtCorners(list(), 0, list().count, {}, PackedPoints<double>{ &points[0].x }, sums);
    return sums;
  }
  /// Unit normals, welded along edges (nullptr: not welded).
  std::vector<glm::dvec3> normals(const PolygonEdges* edges, const std::vector<PointId>& mergeMap, double featureAngle,
    WeldSummary* summary = nullptr) const
  {
    auto welded = sums().points;
    if (edges)
    {
      weldCopies(welded, *edges, areas(), mergeMap, featureAngle, summary);
    }
    std::vector<glm::dvec3> unit;
    for (const CornerSum& sum : welded)
    {
      unit.push_back(unitNormal(sum.area));
    }
    return unit;
  }
};

/// A roof: two unit right triangles meeting at the ridge along x, each sloping down at
/// `slope` radians from the horizontal, so that the faces meet at a dihedral angle of
/// 2 x slope. Each triangle has its own three points, as a file split at the ridge stores
/// them: points 0-2 and 3-5, with 0 and 3 at the ridge's start and 1 and 4 at its end.
Triangles splitRoof(double slope)
{
  Triangles roof;
  const double y = std::cos(slope), z = -std::sin(slope);
  roof.points = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, y, z }, { 0, 0, 0 }, { 1, 0, 0 }, { 0, -y, z } };
  roof.add(0, 1, 2); // normal (0, -z, y) rotated: faces up and toward +y
  roof.add(4, 3, 5); // faces up and toward -y
  return roof;
}

const std::vector<PointId> roofMergeMap{ 0, 1, 2, 0, 1, 5 };

void expectNear(const glm::dvec3& actual, const glm::dvec3& expected, double tolerance)
{
  EXPECT_NEAR(actual.x, expected.x, tolerance);
  EXPECT_NEAR(actual.y, expected.y, tolerance);
  EXPECT_NEAR(actual.z, expected.z, tolerance);
}

TEST(PointNormals, AreaVectorIsHalfTheCrossProduct)
{
  Triangles quad;
  quad.points = { { 0, 0, 0 }, { 2, 0, 0 }, { 2, 3, 0 }, { 0, 3, 0 } };
  quad.offsets = { 0, 4 };
  quad.connectivity = { 0, 1, 2, 3 };
  const std::vector<glm::dvec3> areas = quad.areas();
  ASSERT_EQ(areas.size(), 1u);
  EXPECT_EQ(areas[0], glm::dvec3(0, 0, 6)); // a 2 x 3 rectangle, wound anticlockwise about +z
}

TEST(PointNormals, AreaWeightedAtASharedPoint)
{
  // A small and a large triangle sharing point 0, at right angles: the normal at 0 leans to
  // the large one in the ratio of their areas (1/2 against 2).
  Triangles fan;
  fan.points = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 2 }, { 0, 2, 0 } };
  fan.add(0, 1, 2); // area 1/2, normal +z
  fan.add(0, 3, 4); // area 2, in the plane x = 0, normal -x
  const std::vector<glm::dvec3> unit = fan.normals(nullptr, {}, 80.0);
  expectNear(unit[0], glm::dvec3(-2.0, 0, 0.5) / std::sqrt(4.25), 1e-15);
  expectNear(unit[1], glm::dvec3(0, 0, 1), 0);
}

TEST(PointNormals, CopiesAcrossASmoothSeamShareOneNormal)
{
  const Triangles roof = splitRoof(20.0 * M_PI / 180.0); // faces meet at 40 degrees
  const PolygonEdges edges(roof.list(), roofMergeMap);
  WeldSummary summary;
  const std::vector<glm::dvec3> unit = roof.normals(&edges, roofMergeMap, 80.0, &summary);
  // Both faces have the same area, so the ridge's normal is straight up.
  for (std::size_t ridge : { 0, 1, 3, 4 })
  {
    expectNear(unit[ridge], glm::dvec3(0, 0, 1), 1e-15);
  }
  EXPECT_EQ(unit[0], unit[3]);
  EXPECT_EQ(unit[1], unit[4]);
  EXPECT_EQ(summary.sharedPositions, 2u);
  EXPECT_EQ(summary.pointsAveraged, 4u);
  EXPECT_EQ(summary.pointsKeptApart, 0u);
}

TEST(PointNormals, CopiesAtASharpEdgeKeepTheirOwn)
{
  const double slope = 50.0 * M_PI / 180.0; // faces meet at 100 degrees, sharper than 80
  const Triangles roof = splitRoof(slope);
  const PolygonEdges edges(roof.list(), roofMergeMap);
  WeldSummary summary;
  const std::vector<glm::dvec3> unit = roof.normals(&edges, roofMergeMap, 80.0, &summary);
  const glm::dvec3 towardPlusY(0, std::sin(slope), std::cos(slope));
  const glm::dvec3 towardMinusY(0, -std::sin(slope), std::cos(slope));
  expectNear(unit[0], towardPlusY, 1e-15);
  expectNear(unit[3], towardMinusY, 1e-15);
  EXPECT_EQ(summary.pointsKeptApart, 4u);
  // A feature angle above the edge's 100 degrees welds them after all.
  const std::vector<glm::dvec3> welded = roof.normals(&edges, roofMergeMap, 101.0);
  expectNear(welded[0], glm::dvec3(0, 0, 1), 1e-15);
}

TEST(PointNormals, WithoutWeldingEachCopyHasItsFacesNormal)
{
  const double slope = 20.0 * M_PI / 180.0;
  const Triangles roof = splitRoof(slope);
  const std::vector<glm::dvec3> unit = roof.normals(nullptr, {}, 80.0);
  expectNear(unit[0], glm::dvec3(0, std::sin(slope), std::cos(slope)), 1e-15);
  expectNear(unit[3], glm::dvec3(0, -std::sin(slope), std::cos(slope)), 1e-15);
}

TEST(PointNormals, PointsWithoutAreaHaveTheZeroNormal)
{
  Triangles mesh;
  mesh.points = { { 0, 0, 0 }, { 1, 0, 0 }, { 2, 0, 0 }, { 5, 5, 5 } }; // collinear, and an isolated point
  mesh.add(0, 1, 2);
  mesh.offsets.push_back(mesh.offsets.back()); // a polygon with no points at all
  const std::vector<glm::dvec3> unit = mesh.normals(nullptr, {}, 80.0);
  for (const glm::dvec3& n : unit)
  {
    EXPECT_EQ(n, glm::dvec3(0.0));
  }
}

TEST(PointNormals, WindingTestFindsEdgesTraversedTwiceTheSameWay)
{
  Triangles square;
  square.points = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 } };
  square.add(0, 1, 2);
  square.add(0, 2, 3); // traverses 2 -> 0, the first traverses 0 -> 2: consistent
  EXPECT_EQ(PolygonEdges(square.list(), {}).inconsistentCount(), 0u);
  Triangles turned = square;
  turned.connectivity = { 0, 1, 2, 0, 3, 2 }; // the second now traverses 0 -> 2 too
  EXPECT_EQ(PolygonEdges(turned.list(), {}).inconsistentCount(), 1u);
  // On a split roof the edge joins only through the merge map.
  Triangles roof = splitRoof(0.3);
  roof.connectivity = { 0, 1, 2, 3, 4, 5 }; // both traverse the ridge from its start
  EXPECT_EQ(PolygonEdges(roof.list(), {}).inconsistentCount(), 0u);
  EXPECT_EQ(PolygonEdges(roof.list(), roofMergeMap).inconsistentCount(), 1u);
}

/// A regular tetrahedron's four faces, wound outward: a closed, consistent surface.
Triangles tetrahedron()
{
  Triangles solid;
  solid.points = { { 1, 1, 1 }, { 1, -1, -1 }, { -1, 1, -1 }, { -1, -1, 1 } };
  solid.add(0, 1, 2);
  solid.add(0, 3, 1);
  solid.add(0, 2, 3);
  solid.add(1, 3, 2);
  return solid;
}

TEST(PointNormals, EdgeBalanceIsZeroOnlyWhereTheSurfaceClosesConsistently)
{
  const Triangles closed = tetrahedron();
  EXPECT_TRUE(unbalancedPoints(closed.sums().points, 0, closed.points.size()).empty());
  // Without its last face, the three points of that face's rim are on a boundary.
  Triangles open = closed;
  open.offsets.pop_back();
  open.connectivity.resize(9);
  EXPECT_EQ(unbalancedPoints(open.sums().points, 0, open.points.size()), (std::vector<PointId>{ 1, 2, 3 }));
  // One face turned round: every edge of it is traversed twice in one direction.
  Triangles turned = closed;
  std::swap(turned.connectivity[10], turned.connectivity[11]); // 1, 2, 3
  EXPECT_EQ(unbalancedPoints(turned.sums().points, 0, turned.points.size()), (std::vector<PointId>{ 1, 2, 3 }));
  EXPECT_EQ(PolygonEdges(turned.list(), {}).inconsistentCount(), 3u);
}

TEST(PointNormals, SumsAtCornersAreTheAreaVectorsAroundEachPoint)
{
  const Triangles solid = tetrahedron();
  const CornerSums sums = solid.sums();
  const std::vector<glm::dvec3> areas = solid.areas();
  EXPECT_EQ(sums.points[0].area, areas[0] + areas[1] + areas[2]);
  EXPECT_EQ(sums.points[3].area, areas[1] + areas[2] + areas[3]);
  // Each face's vector area points away from the opposite corner: the normals point out.
  for (std::size_t i = 0; i < 4; ++i)
  {
    EXPECT_GT(glm::dot(sums.points[i].area, solid.points[i]), 0.0);
  }
}

TEST(PointNormals, WindingOfAClosedSurfaceHasNoVectorAreaAndThreeTimesItsVolumeAsFlux)
{
  // The tetrahedron's corners are alternate corners of the cube [-1, 1]^3: its volume is the
  // cube's 8 less four corner pyramids of 4/3, 8/3; its flux about the origin 3 x 8/3 = 8.
  const NormalOrientation outward = tetrahedron().sums().winding.result();
  EXPECT_NEAR(outward.closure, 0.0, 1e-15);
  EXPECT_NEAR(outward.flux, 8.0, 1e-14);
  EXPECT_FALSE(outward.pointsInward());
  Triangles inside = tetrahedron();
  std::reverse(inside.connectivity.begin(), inside.connectivity.end()); // every face turned round
  inside.offsets = { 0, 3, 6, 9, 12 };
  EXPECT_NEAR(inside.sums().winding.result().flux, -8.0, 1e-14);
  EXPECT_TRUE(inside.sums().winding.result().pointsInward());
}

// The winding's sums are exact: polygons whose areas span twelve decades, which a running sum
// of doubles adds differently in each order, give the same bits in any order and grouping (as
// the pieces of a split mesh give them), and the sums of doubles to their rounding.
TEST(PointNormals, WindingSumsAreTheSameInAnyOrder)
{
  const glm::dvec3 centre(0.1, -0.2, 0.3);
  const double radius = 2.0;
  struct Polygon
  {
    glm::dvec3 vectorArea, centroid;
  };
  std::vector<Polygon> polygons;
  for (int k = 0; k < 1000; ++k)
  {
    const double size = std::pow(10.0, -(k % 13)); // 1 to 1e-12
    const glm::dvec3 direction(std::sin(k * 1.3), std::cos(k * 0.7), std::sin(k * 2.9 + 1.0));
    polygons.push_back({ size * direction, centre + 0.5 * glm::dvec3(std::cos(k), std::sin(k * 0.3), 0.2) });
  }
  auto summed = [&](const std::vector<std::size_t>& order, std::size_t split)
  {
    NormalOrientationAccumulator first(centre, radius), second(centre, radius);
    for (std::size_t i = 0; i < order.size(); ++i)
    {
      const Polygon& p = polygons[order[i]];
      (i < split ? first : second).add(p.vectorArea, glm::length(p.vectorArea), p.centroid);
    }
    first.add(second);
    return first;
  };
  std::vector<std::size_t> forward(polygons.size()), backward;
  std::iota(forward.begin(), forward.end(), std::size_t(0));
  backward.assign(forward.rbegin(), forward.rend());
  const NormalOrientationAccumulator inOrder = summed(forward, forward.size());
  for (const auto& [order, split] : { std::pair{ backward, backward.size() }, std::pair{ forward, std::size_t(377) },
         std::pair{ backward, std::size_t(1) } })
  {
    EXPECT_EQ(summed(order, split).words(), inOrder.words());
  }
  long double vectorArea[3] = { 0, 0, 0 }, area = 0, flux = 0;
  for (const Polygon& p : polygons)
  {
    for (int c = 0; c < 3; ++c)
    {
      vectorArea[c] += p.vectorArea[c];
    }
    area += glm::length(p.vectorArea);
    flux += glm::dot(p.vectorArea, p.centroid - centre);
  }
  const NormalOrientation result = inOrder.result();
  const double closure = static_cast<double>(
    std::sqrt(vectorArea[0] * vectorArea[0] + vectorArea[1] * vectorArea[1] + vectorArea[2] * vectorArea[2]) / area);
  // The grid is 2^-57 of the largest polygon's term: about 1e-17 here, a thousand of them.
  EXPECT_NEAR(result.closure, closure, 1e-13);
  EXPECT_NEAR(result.flux, static_cast<double>(flux), 1e-13);

  // A coordinate that is not finite makes no orientation: the mesh is taken as open.
  NormalOrientationAccumulator withNaN = inOrder;
  withNaN.add(glm::dvec3(std::nan(""), 0.0, 0.0), 1.0, centre);
  EXPECT_EQ(withNaN.result().closure, 1.0);
  EXPECT_EQ(withNaN.result().flux, 0.0);
}

TEST(PointNormals, SubsetHoldsThePolygonsWithAnEdgeBetweenListedPoints)
{
  const Triangles solid = tetrahedron();
  // Points 1 and 3 share an edge in faces 1 (0, 3, 1) and 3 (1, 3, 2); 0 and 2 alone share
  // edges with unlisted points only.
  const std::vector<std::uint8_t> listed{ 0, 1, 0, 1 };
  std::vector<std::size_t> chosen;
  for (std::size_t k = 0; k < solid.list().count; ++k)
  {
    if (hasEdgeBetween(solid.list(), k, listed))
    {
      chosen.push_back(k);
    }
  }
  EXPECT_EQ(chosen, (std::vector<std::size_t>{ 1, 3 }));
  const PolygonSubset subset(solid.list(), chosen);
  ASSERT_EQ(subset.list().count, 2u);
  EXPECT_EQ(std::vector<PointId>(subset.list().ids(0), subset.list().ids(0) + 3), (std::vector<PointId>{ 0, 3, 1 }));
  EXPECT_EQ(std::vector<PointId>(subset.list().ids(1), subset.list().ids(1) + 3), (std::vector<PointId>{ 1, 3, 2 }));
  EXPECT_EQ(subset.original(1), 3u);
}

TEST(PointNormals, CoincidentPointsMapToTheLowestIdAtTheirPosition)
{
  const double nan = std::nan("");
  const std::vector<glm::dvec3> points = { { 0, 0, 0 }, { 1, 2, 3 }, { -0.0, 0, 0 }, { 1, 2, 3 }, { 1, 2, 3 },
    { nan, 0, 0 }, { nan, 0, 0 }, { 0, 0, 0 } };
  auto at = [&points](PointId id) { return points[static_cast<std::size_t>(id)]; };
  // Point 7 is not a candidate, so it stays itself; -0 is the same position as +0; NaN
  // positions are nobody's.
  EXPECT_EQ(
    coincidentPointMap({ 0, 1, 2, 3, 4, 5, 6 }, points.size(), at), (std::vector<PointId>{ 0, 1, 0, 1, 1, 5, 6, 7 }));
  EXPECT_TRUE(coincidentPointMap({ 0, 1, 5, 6 }, points.size(), at).empty());
}
}
