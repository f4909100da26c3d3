#pragma once
// Meshes with known geometry for the filter tests.
#include "vtkAppendPolyData.h"
#include "vtkDoubleArray.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkSphereSource.h"
#include "vtkTriangleFilter.h"

#include <glm/vec3.hpp>

#include <cmath>

namespace shadelab::testing
{
/// A tessellated sphere in float64 whose point normals are exactly (p - centre)/radius, so
/// closed forms in the polar angle hold at every vertex.
inline vtkSmartPointer<vtkPolyData> exactSphere(
  int resolution, const glm::dvec3& centre = glm::dvec3(0.0), double radius = 1.0)
{
  vtkNew<vtkSphereSource> source;
  source->SetThetaResolution(resolution);
  source->SetPhiResolution(resolution);
  source->SetRadius(radius);
  source->SetCenter(centre.x, centre.y, centre.z);
  source->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  source->Update();
  auto sphere = vtkSmartPointer<vtkPolyData>::New();
  sphere->ShallowCopy(source->GetOutput());
  auto normals = vtkSmartPointer<vtkDoubleArray>::New();
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  normals->SetNumberOfTuples(sphere->GetNumberOfPoints());
  for (vtkIdType i = 0; i < sphere->GetNumberOfPoints(); ++i)
  {
    double p[3];
    sphere->GetPoint(i, p);
    const double n[3] = { (p[0] - centre.x) / radius, (p[1] - centre.y) / radius, (p[2] - centre.z) / radius };
    const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    normals->SetTuple3(i, n[0] / length, n[1] / length, n[2] / length);
  }
  sphere->GetPointData()->SetNormals(normals);
  return sphere;
}

/// An exactSphere over the square [-2, 2]^2 at z = 0 (facing +z, planeResolution cells a side),
/// all triangles.
inline vtkSmartPointer<vtkPolyData> sphereOverSquare(
  int planeResolution, int sphereResolution, const glm::dvec3& centre, double radius)
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-2, -2, 0);
  plane->SetPoint1(2, -2, 0);
  plane->SetPoint2(-2, 2, 0);
  plane->SetResolution(planeResolution, planeResolution);
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(plane->GetOutputPort());
  vtkNew<vtkAppendPolyData> both;
  both->AddInputConnection(triangles->GetOutputPort());
  both->AddInputData(exactSphere(sphereResolution, centre, radius));
  both->Update();
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->ShallowCopy(both->GetOutput());
  return mesh;
}
}
