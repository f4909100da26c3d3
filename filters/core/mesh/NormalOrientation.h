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

#include <cmath>
#include <cstddef>
#include <vector>

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

/// The sums behind closure and flux, kept in fixed point: each polygon's terms are rounded to a
/// grid set by the mesh's size and added as integers, so the sums are exact and the same in any
/// order. A mesh split over processes sums its pieces apart and adds the pieces' sums: the
/// result is the single process's to the bit, which a running sum of doubles would not be.
class NormalOrientationAccumulator
{
public:
  /// Sums about `centre` for a mesh within `radius` of it (half its bounding box's diagonal),
  /// which sets the grid: about 2^-59 of the largest term a polygon of the mesh can give.
  NormalOrientationAccumulator(const glm::dvec3& centre, double radius);

  /// One triangle: its corners and the normals stored at them.
  void addTriangle(const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& p2, const glm::dvec3& n0,
    const glm::dvec3& n1, const glm::dvec3& n2);

  /// One polygon: its vector area (A n), its area A, and its centroid.
  void add(const glm::dvec3& vectorArea, double area, const glm::dvec3& centroid)
  {
    addTerm(vectorArea_[0], vectorArea.x * areaScale_);
    addTerm(vectorArea_[1], vectorArea.y * areaScale_);
    addTerm(vectorArea_[2], vectorArea.z * areaScale_);
    addTerm(area_, area * areaScale_);
    addTerm(flux_, glm::dot(vectorArea, centroid - centre_) * fluxScale_);
  }

  /// Adds another accumulator's polygons (about the same centre and radius).
  void add(const NormalOrientationAccumulator& other);

  /// The sums as 64-bit words, for another process's addWords.
  std::vector<long long> words() const;
  /// Adds the sums another accumulator (about the same centre and radius) gave as words().
  void addWords(const long long* words);
  static constexpr std::size_t wordCount = 11;

  NormalOrientation result() const;

private:
  __extension__ typedef __int128 FixedSum; // 2^127: room for 2^67 terms below 2^60

  void addTerm(FixedSum& sum, double scaled)
  {
    constexpr double largestTerm = 1152921504606846976.0; // 2^60
    if (!(std::fabs(scaled) < largestTerm))
    {
      representable_ = false; // a coordinate that is not finite, or outside the radius
      return;
    }
    sum += std::llrint(scaled);
  }

  glm::dvec3 centre_;
  double areaScale_ = 1.0; // grid steps per unit of area, a power of two
  double fluxScale_ = 1.0; // grid steps per unit of area x length, a power of two
  FixedSum vectorArea_[3] = { 0, 0, 0 };
  FixedSum area_ = 0;
  FixedSum flux_ = 0;
  bool representable_ = true;
};
}
