#pragma once
// VTK-free meshes with known geometry for the core's tests (visibility, interreflection):
// points with unit normals, triangles, and the BVH over them.
#include "OccluderMesh.h"
#include "Visibility.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <vector>

namespace shadelab::testing
{
/// A polygon mesh with a unit normal per point.
struct Mesh
{
  std::vector<glm::dvec3> points, normals;
  std::vector<PointId> offsets{ 0 };
  std::vector<PointId> connectivity;

  PointId addPoint(const glm::dvec3& p, const glm::dvec3& n)
  {
    points.push_back(p);
    normals.push_back(glm::normalize(n));
    return static_cast<PointId>(points.size() - 1);
  }
  void addTriangle(PointId a, PointId b, PointId c)
  {
    connectivity.insert(connectivity.end(), { a, b, c });
    offsets.push_back(static_cast<PointId>(connectivity.size()));
  }
  PolygonList list() const { return { offsets.data(), connectivity.data(), offsets.size() - 1 }; }
  OccluderMesh occluders() const { return OccluderMesh(PackedPoints<double>{ &points[0].x }, points.size(), list()); }
  RayVertex vertex(std::size_t i) const { return { points[i], normals[i], static_cast<PointId>(i) }; }
  /// The same mesh at world = offset + scale * p.
  Mesh placed(const glm::dvec3& offset, double scale) const
  {
    Mesh moved = *this;
    for (glm::dvec3& p : moved.points)
    {
      p = offset + scale * p;
    }
    return moved;
  }
};

/// A zone of a UV sphere, polar angles thetaFrom to pi (the whole sphere from 0, a bowl
/// from above 0), with its points on the sphere and radial normals: rows x columns quads,
/// split into triangles, facing out (normals and winding) or in.
inline void addSphereZone(
  Mesh& mesh, const glm::dvec3& centre, double radius, int rows, int columns, double thetaFrom, bool inward = false)
{
  const PointId first = static_cast<PointId>(mesh.points.size());
  for (int i = 0; i <= rows; ++i)
  {
    const double theta = thetaFrom + (M_PI - thetaFrom) * i / rows;
    for (int j = 0; j < columns; ++j)
    {
      const double phi = 2 * M_PI * j / columns;
      const glm::dvec3 n(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
      mesh.addPoint(centre + radius * n, inward ? -n : n);
    }
  }
  auto id = [&](int i, int j) { return first + static_cast<PointId>(i * columns + (j % columns)); };
  for (int i = 0; i < rows; ++i)
  {
    for (int j = 0; j < columns; ++j)
    {
      // Rows at the poles collapse to degenerate triangles, which hit nothing.
      if (inward)
      {
        mesh.addTriangle(id(i, j), id(i + 1, j + 1), id(i + 1, j));
        mesh.addTriangle(id(i, j), id(i, j + 1), id(i + 1, j + 1));
      }
      else
      {
        mesh.addTriangle(id(i, j), id(i + 1, j), id(i + 1, j + 1));
        mesh.addTriangle(id(i, j), id(i + 1, j + 1), id(i, j + 1));
      }
    }
  }
}

/// A whole UV sphere (addSphereZone from the pole).
inline void addSphere(Mesh& mesh, const glm::dvec3& centre, double radius, int rows, int columns, bool inward = false)
{
  addSphereZone(mesh, centre, radius, rows, columns, 0.0, inward);
}

/// The square [-half, half]^2 at z = 0, facing +z, in cells x cells quads.
inline void addPlane(Mesh& mesh, double half, int cells)
{
  const PointId first = static_cast<PointId>(mesh.points.size());
  for (int i = 0; i <= cells; ++i)
  {
    for (int j = 0; j <= cells; ++j)
    {
      mesh.addPoint({ -half + 2 * half * i / cells, -half + 2 * half * j / cells, 0 }, { 0, 0, 1 });
    }
  }
  auto id = [&](int i, int j) { return first + static_cast<PointId>(i * (cells + 1) + j); };
  for (int i = 0; i < cells; ++i)
  {
    for (int j = 0; j < cells; ++j)
    {
      mesh.addTriangle(id(i, j), id(i + 1, j), id(i + 1, j + 1));
      mesh.addTriangle(id(i, j), id(i + 1, j + 1), id(i, j + 1));
    }
  }
}
}
