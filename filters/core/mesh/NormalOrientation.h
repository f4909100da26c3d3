#pragma once
// Do a mesh's normals point out of it or into it? Real meshes wind their triangles either
// way (the Stanford bunny's computed normals point in), and inward normals shade a lit
// object dark. Decided from two surface integrals, with no need for a watertight mesh:
//  - closure = |sum of A n| / sum of A over triangles. A closed surface has zero vector area
//    (the divergence theorem with a constant field), so closure is 0 for a closed mesh, small
//    for one with small holes and 1 for a flat sheet.
//  - flux = sum of A n.(g - c), g the triangle's centroid and c a centre. For a closed
//    surface this is 3 x its volume with outward normals and -3 x it with inward ones.
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace shadelab
{
struct NormalOrientation
{
  double closure = 1.0;
  double flux = 0.0;
  /// Closure below this counts as "closed or nearly closed": holes with at most a tenth of
  /// the surface's projected area cannot flip the sign of the flux of a convex-ish shape.
  static constexpr double nearlyClosedBelow = 0.1;

  bool nearlyClosed() const { return closure < nearlyClosedBelow; }
  bool pointsInward() const { return nearlyClosed() && flux < 0.0; }
};

class NormalOrientationAccumulator
{
public:
  explicit NormalOrientationAccumulator(const glm::dvec3& centre)
    : centre_(centre)
  {
  }

  /// One triangle: its corners and the normals stored at them.
  void addTriangle(const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& p2, const glm::dvec3& n0,
    const glm::dvec3& n1, const glm::dvec3& n2);

  /// One polygon: its vector area (A n), its area A, and its centroid.
  void add(const glm::dvec3& vectorArea, double area, const glm::dvec3& centroid)
  {
    vectorArea_ += vectorArea;
    area_ += area;
    flux_ += glm::dot(vectorArea, centroid - centre_);
  }

  /// Adds another accumulator's polygons (about the same centre).
  void add(const NormalOrientationAccumulator& other)
  {
    vectorArea_ += other.vectorArea_;
    area_ += other.area_;
    flux_ += other.flux_;
  }

  NormalOrientation result() const;

private:
  glm::dvec3 centre_;
  glm::dvec3 vectorArea_{ 0.0 };
  double area_ = 0.0;
  double flux_ = 0.0;
};
}
