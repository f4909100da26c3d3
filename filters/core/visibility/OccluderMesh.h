#pragma once
// A mesh's triangles as occluders of rays: an Embree 3 BVH, built once, queried from any
// number of threads at once.
//
// Embree works in float32, so the triangles go into a frame where the mesh's bounding sphere
// is the unit sphere: a mesh far from the origin or of any size keeps float32's relative
// precision, and the ray offsets (RayOrigin.h) mean the same on every mesh.
#include "PointNormals.h"

#include <glm/common.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

namespace shadelab
{
/// Where a ray goes: from a surface point, along a unit direction, up to a distance (infinite:
/// to the end of the scene). In the mesh's own coordinates.
struct SurfaceRay
{
  glm::dvec3 point{ 0.0 }; // the surface point it leaves
  glm::dvec3 side{ 0.0 };  // the unit normal of the side it leaves from
  glm::dvec3 direction{ 0.0 };
  double maxDistance = std::numeric_limits<double>::infinity();
  /// The point id of the vertex it leaves, or -1. Where the point has copies (a seam, or a hard
  /// edge written with a point per face), the ray leaves off the faces of all of them.
  PointId vertex = -1;
};

class OccluderMesh
{
public:
  /// The polygons (split into fans of triangles) over pointCount points; pointAt(id) gives a
  /// point in the mesh's coordinates.
  template<typename Real>
  OccluderMesh(PackedPoints<Real> points, std::size_t pointCount, const PolygonList& polygons)
    : OccluderMesh(UnitFrame::of(points, pointCount), polygons)
  {
  }
  ~OccluderMesh();
  OccluderMesh(const OccluderMesh&) = delete;
  OccluderMesh& operator=(const OccluderMesh&) = delete;

  /// Rays traced together: Embree traces them as one packet, which is faster than one by one
  /// where their paths begin alike (rays from one vertex, or from neighbours to one light). 64
  /// ambient occlusion rays per vertex on the bunny took 0.42 s one by one, 0.31 s in packets
  /// of 8 and 0.27 s in packets of 16, on 2 cores; Embree emulates 16-wide packets where the
  /// processor has no AVX-512.
  static constexpr int bundleSize = 16;

  /// A ray in the BVH's frame, its origin moved off the surface (RayOrigin.h). The frame only
  /// moves and scales, so directions are the same in both: the rays of one vertex differ only
  /// in their direction, and its start is computed once for all of them.
  struct FrameRay
  {
    glm::vec3 origin{ 0.0f };
    glm::vec3 direction{ 0.0f };
    float maxDistance = std::numeric_limits<float>::infinity();
  };
  FrameRay inFrame(const SurfaceRay& ray) const;
  /// A distance in the mesh's coordinates as the BVH's frame measures it.
  float frameDistance(double distance) const { return static_cast<float>(distance / frame_.radius); }

  /// Which of rays[0..count-1] (count <= bundleSize) triangles block: bit j for rays[j].
  unsigned occluded(const FrameRay* rays, int count) const;

  /// Where a ray first meets a triangle: the triangle's index and the hit's barycentric
  /// coordinates (u, v) there, the point (1 - u - v) a + u b + v c of its corners (a, b, c), as
  /// corners() gives them. A ray that meets none has the triangle noTriangle.
  struct RayHit
  {
    static constexpr std::uint32_t noTriangle = 0xFFFFFFFFu;
    std::uint32_t triangle = noTriangle;
    float u = 0, v = 0;
    /// Whether the ray met the triangle's back (gatherHits says which side that is).
    bool onBack = false;
  };
  /// The first hits of rays[0..count-1] (count <= bundleSize), traced as one packet.
  void firstHits(const FrameRay* rays, int count, RayHit* hits) const;
  /// The point ids of a triangle's corners (a polygon's fan of triangles: its first point, then
  /// each pair of neighbours), in the polygon's order.
  std::array<std::uint32_t, 3> corners(std::size_t triangle) const
  {
    return { triangles_[3 * triangle], triangles_[3 * triangle + 1], triangles_[3 * triangle + 2] };
  }

  /// A triangle's area vector (twice its area, along its normal by the corners' order), in the
  /// BVH's frame, which only moves and scales: its direction is the mesh's.
  glm::dvec3 areaVector(std::size_t triangle) const;

  /// Whether the first triangle the ray meets has a corner at `point` (in the mesh's
  /// coordinates), the point of id vertex (or -1) that the ray leaves: the vertex itself, or a
  /// copy of it where the mesh is split at a seam or a hard edge, which has another point id
  /// but the same coordinates. With the point's id, a ray that moves away from the planes of
  /// all the point's own triangles is answered without a search (ownNormalCones_: on the
  /// bunny x64, the flag's searches for the benchmark's blocked shadow rays took 12.5 ms rather
  /// than 37 to 39 on one thread), and the search otherwise ends where the point's own triangles
  /// end (ownReach_), which makes it short: about half the time that a search to the ray's end
  /// took, per blocked shadow ray on the bunny.
  bool firstHitHasCorner(const FrameRay& ray, const glm::dvec3& point, PointId vertex = -1) const;

  /// Whether a blocked ray stays blocked once the point's own facets on its smooth surface are
  /// passed over (docs/formulas.md section 20, the shadow terminator): where the first
  /// triangle the ray meets lies around the point on its surface (aroundOnItsSurface), the ray
  /// starts again from the point lifted along the side it leaves from, above every corner of
  /// those triangles (a terminator offset, as Blender's at a vertex). A copy's triangle across
  /// a hard edge still blocks it, and so does every other triangle.
  bool hiddenPastOwnFacets(const SurfaceRay& ray) const;

  std::size_t triangleCount() const { return triangles_.size() / 3; }

  /// Unit vectors within an angle of an axis, in 8 bytes: the axis and the cosine of the
  /// half-angle in steps of 1/32767 (the cosine rounded down, so the cone holds what it was
  /// made for). A cosine of 0 or less holds nothing that a test may rely on.
  class NormalCone
  {
  public:
    /// A cone of no width about the axis nearest unitAxis that the steps hold.
    static NormalCone of(const glm::dvec3& unitAxis);
    /// The same axis, with a half-angle of at least acos(cosine).
    NormalCone withCosine(double cosine) const;
    /// The stored axis, of unit length (or 0).
    glm::dvec3 axis() const;
    double cosine() const { return cosine_ / steps; }

  private:
    static constexpr double steps = 32767;
    std::int16_t axis_[3] = { 0, 0, 0 };
    std::int16_t cosine_ = -32767;
  };

  /// Throws std::runtime_error if Embree reported an error since the BVH was built (a ray it
  /// could not trace reads as unblocked, so a run checks this after casting).
  void checkTracing() const;

  /// Frees the BVH (most of what the mesh holds) once every ray is traced: corners() and
  /// areaVector() still answer, and a ray traced after it throws std::logic_error.
  /// Interreflection's sweeps need the corners alone.
  void releaseTracing();

private:
  /// The points in the frame where the mesh's bounding sphere is the unit sphere.
  struct UnitFrame
  {
    glm::dvec3 centre{ 0.0 };
    double radius = 1;
    std::vector<float> vertices; // x, y, z per point, then one padding float

    glm::dvec3 toUnit(const glm::dvec3& p) const { return (p - centre) / radius; }
    template<typename Real>
    static UnitFrame of(PackedPoints<Real> points, std::size_t pointCount);
  };
  OccluderMesh(UnitFrame frame, const PolygonList& polygons);
  /// The unit normal of the side a ray from the surface leaves from: the joint normal of the
  /// point and its copies where it has copies, else ray.side, in the BVH's frame.
  glm::vec3 leavingSide(const SurfaceRay& ray) const;
  /// The triangle the ray meets first, or -1.
  std::int64_t firstHit(const FrameRay& ray) const;
  /// The triangle the ray from the point of id vertex (or -1) at unitPoint meets first, if it
  /// can be one of the point's own triangles (within their reach, and unless the ray leaves
  /// all their planes); -1 otherwise.
  std::int64_t firstHitNearby(const FrameRay& ray, const glm::vec3& unitPoint, PointId vertex) const;
  /// Whether triangle t has a corner at unitPoint (in the unit frame).
  bool hasCornerAt(std::size_t t, const glm::vec3& unitPoint) const;
  /// Whether triangle t lies around the point of id vertex at `point` (in the unit frame) on the surface its
  /// normal describes: the point is its corner, or a copy of the point is and the triangle's
  /// normal is within 30 degrees of side (a seam, not a hard edge).
  bool aroundOnItsSurface(std::size_t t, PointId vertex, const glm::vec3& point, const glm::dvec3& side) const;
  /// How far above the plane through `point` (in the unit frame) with unit normal side the
  /// corners of the triangles around the point on its surface reach (0 where none rises).
  double ownFacetsRise(const glm::vec3& point, PointId vertex, const glm::dvec3& side) const;
  /// How far along the ray from the point of id vertex (or -1) its own triangles can be met.
  float ownTrianglesReach(const FrameRay& ray, const glm::vec3& unitPoint, PointId vertex) const;
  /// Whether the ray, from the point (in the unit frame) of index `point`, starts on one side of
  /// the planes of all the point's own triangles and moves away from them: it meets none of them.
  bool leavesAllOwnPlanes(const FrameRay& ray, const glm::vec3& unitPoint, std::size_t point) const;

  UnitFrame frame_;
  std::vector<std::uint32_t> triangles_; // three point ids per triangle
  /// Per point with copies (points of the same coordinates), the unit sum of the area vectors
  /// of the triangles around it and its copies; (0, 0, 0) elsewhere. Empty when no point has a
  /// copy. At a concave hard edge, the floor's copy of a point lies in the wall's plane: a ray
  /// moved off the floor alone would start on the wall and meet it at once.
  std::vector<glm::vec3> jointNormals_;
  /// Per point, the largest distance in the unit frame from it to a corner of a triangle that
  /// has it, or a copy of it, as a corner: where a ray from it can meet its own triangles.
  std::vector<float> ownReach_;
  /// Per point, a cone around the normals of its own triangles (those with it or a copy of it
  /// as a corner): a blocked shadow ray that moves away from all their planes needs no search
  /// for its first hit.
  std::vector<NormalCone> ownNormalCones_;
  struct Embree;
  std::unique_ptr<Embree> embree_;
};

template<typename Real>
OccluderMesh::UnitFrame OccluderMesh::UnitFrame::of(PackedPoints<Real> points, std::size_t pointCount)
{
  // The bounding box's centre and the largest distance from it, over the finite points: a
  // point with a NaN or Inf coordinate goes into the frame as NaN, which Embree's builder
  // leaves out with its triangles.
  auto finite = [](const glm::dvec3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); };
  UnitFrame frame;
  glm::dvec3 low(std::numeric_limits<double>::infinity()), high(-std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < pointCount; ++i)
  {
    const glm::dvec3 p = points(static_cast<PointId>(i));
    low = finite(p) ? glm::min(low, p) : low;
    high = finite(p) ? glm::max(high, p) : high;
  }
  frame.centre = low.x <= high.x ? 0.5 * (low + high) : glm::dvec3(0.0);
  double radiusSquared = 0;
  for (std::size_t i = 0; i < pointCount; ++i)
  {
    const glm::dvec3 d = points(static_cast<PointId>(i)) - frame.centre;
    radiusSquared = finite(d) ? std::max(radiusSquared, d.x * d.x + d.y * d.y + d.z * d.z) : radiusSquared;
  }
  frame.radius = radiusSquared > 0 && std::isfinite(radiusSquared) ? std::sqrt(radiusSquared) : 1.0;
  frame.vertices.resize(3 * pointCount + 1, 0.0f); // Embree reads 16 bytes at the last vertex
  for (std::size_t i = 0; i < pointCount; ++i)
  {
    const glm::dvec3 p = points(static_cast<PointId>(i));
    const glm::dvec3 local = finite(p) ? frame.toUnit(p) : glm::dvec3(std::numeric_limits<double>::quiet_NaN());
    frame.vertices[3 * i] = static_cast<float>(local.x);
    frame.vertices[3 * i + 1] = static_cast<float>(local.y);
    frame.vertices[3 * i + 2] = static_cast<float>(local.z);
  }
  return frame;
}
}
