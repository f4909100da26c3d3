// vtkShadingNormalsFilter on meshes as files store them: split at texture seams (spot.obj),
// split at sharp edges on purpose (a cube with a point set per face), stored unsplit (a cube
// with 8 points), and wound inconsistently.
#include "MeshFiles.h"
#include "TestPaths.h"

#include "vtkShadingNormalsFilter.h"

#include "vtkCellArray.h"
#include "vtkCleanPolyData.h"
#include "vtkCubeSource.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkIdList.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSphereSource.h"
#include "vtkStringArray.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>

namespace
{
using Position = std::array<double, 3>;

vtkSmartPointer<vtkPolyData> withNormals(vtkPolyData* mesh, bool weld = true, double splitAngle = 0)
{
  vtkNew<vtkShadingNormalsFilter> filter;
  filter->SetInputData(mesh);
  filter->SetWeldCoincidentPoints(weld);
  if (splitAngle > 0)
  {
    filter->SplitSharpEdgesOn();
    filter->SetSplitAngle(splitAngle);
  }
  filter->Update();
  auto output = vtkSmartPointer<vtkPolyData>::New();
  output->ShallowCopy(filter->GetOutput());
  return output;
}

std::string reportOf(vtkPolyData* output)
{
  return vtkStringArray::SafeDownCast(output->GetFieldData()->GetAbstractArray("shadelab_normals"))->GetValue(0);
}

/// The normals found at each position, and how many positions hold more than one.
struct NormalsByPosition
{
  std::map<Position, std::vector<Position>> normals;
  std::size_t positionsWithDifferentNormals = 0;
};

NormalsByPosition normalsByPosition(vtkPolyData* mesh)
{
  NormalsByPosition result;
  vtkDataArray* normals = mesh->GetPointData()->GetNormals();
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    Position p, n;
    mesh->GetPoint(i, p.data());
    normals->GetTuple(i, n.data());
    result.normals[p].push_back(n);
  }
  for (const auto& [position, list] : result.normals)
  {
    for (const Position& n : list)
    {
      if (n != list.front())
      {
        ++result.positionsWithDifferentNormals;
        break;
      }
    }
  }
  return result;
}

vtkSmartPointer<vtkPolyData> cubeWithoutNormals(bool merged)
{
  vtkNew<vtkCubeSource> cube; // 6 quads with 4 points each, so each corner is stored 3 times
  vtkNew<vtkCleanPolyData> clean;
  clean->SetInputConnection(cube->GetOutputPort());
  clean->PointMergingOn();
  vtkAlgorithm* source = merged ? static_cast<vtkAlgorithm*>(clean) : cube;
  source->Update();
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->DeepCopy(vtkPolyData::SafeDownCast(source->GetOutputDataObject(0)));
  mesh->GetPointData()->Initialize();
  return mesh;
}

/// |n| = 1 with one component ±1: the normal of one of the cube's faces.
bool isFaceNormal(const double n[3])
{
  int axes = 0;
  for (int c = 0; c < 3; ++c)
  {
    axes += std::abs(n[c]) == 1.0 ? 1 : (n[c] == 0.0 ? 0 : 10);
  }
  return axes == 1;
}

TEST(ShadingNormals, SpotSplitAtItsTextureSeamsShadesSmooth)
{
  vtkSmartPointer<vtkPolyData> spot = shadelab::app::readMesh(shadelab::testing::sourcePath("data/meshes/spot.obj"));
  // vtkOBJReader gives each of the 5,856 triangles its own three points, at 2,930 positions.
  ASSERT_EQ(spot->GetNumberOfPoints(), 17568);
  vtkSmartPointer<vtkPolyData> smooth = withNormals(spot);
  EXPECT_EQ(smooth->GetNumberOfPoints(), 17568);
  const NormalsByPosition welded = normalsByPosition(smooth);
  EXPECT_EQ(welded.normals.size(), 2930u);
  EXPECT_EQ(welded.positionsWithDifferentNormals, 0u); // bit for bit the same at every position
  EXPECT_EQ(reportOf(smooth),
    "The mesh has no point normals: computed area-weighted ones and added them as 'Normals'; 2930 positions are "
    "shared by several points: averaged 17568 points with their copies.");
  // Without welding each point has its own triangle's normal: facets.
  EXPECT_EQ(normalsByPosition(withNormals(spot, false)).positionsWithDifferentNormals, 2930u);
}

TEST(ShadingNormals, ACubeSplitAtItsEdgesKeepsThem)
{
  vtkSmartPointer<vtkPolyData> cube = withNormals(cubeWithoutNormals(false));
  ASSERT_EQ(cube->GetNumberOfPoints(), 24);
  vtkDataArray* normals = cube->GetPointData()->GetNormals();
  for (vtkIdType i = 0; i < 24; ++i)
  {
    double n[3];
    normals->GetTuple(i, n);
    EXPECT_TRUE(isFaceNormal(n)) << i << ": " << n[0] << " " << n[1] << " " << n[2];
  }
  EXPECT_EQ(reportOf(cube),
    "The mesh has no point normals: computed area-weighted ones and added them as 'Normals'; 8 positions are "
    "shared by several points: averaged 0 points with their copies, kept 24 apart at edges sharper than 80 degrees.");
}

TEST(ShadingNormals, AnUnsplitCubeIsSplitOnRequest)
{
  vtkSmartPointer<vtkPolyData> merged = cubeWithoutNormals(true);
  ASSERT_EQ(merged->GetNumberOfPoints(), 8);
  // One normal per corner: the diagonal, the only normal a point shared by three faces can have.
  vtkSmartPointer<vtkPolyData> rounded = withNormals(merged);
  for (vtkIdType i = 0; i < 8; ++i)
  {
    double p[3], n[3];
    rounded->GetPoint(i, p);
    rounded->GetPointData()->GetNormals()->GetTuple(i, n);
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_NEAR(n[c], std::copysign(1.0 / std::sqrt(3.0), p[c]), 1e-7);
    }
  }
  vtkSmartPointer<vtkPolyData> split = withNormals(merged, true, 30.0);
  ASSERT_EQ(split->GetNumberOfPoints(), 24);
  for (vtkIdType i = 0; i < 24; ++i)
  {
    double n[3];
    split->GetPointData()->GetNormals()->GetTuple(i, n);
    EXPECT_TRUE(isFaceNormal(n)) << i;
  }
  EXPECT_EQ(reportOf(split),
    "Split the mesh at edges sharper than 30 degrees (vtkPolyDataNormals): 8 points became 24; computed normals "
    "as 'Normals'.");
}

TEST(ShadingNormals, InconsistentWindingIsTurnedRound)
{
  vtkNew<vtkSphereSource> source;
  source->SetThetaResolution(24);
  source->SetPhiResolution(12);
  source->Update();
  vtkNew<vtkPolyData> sphere;
  sphere->DeepCopy(source->GetOutput());
  sphere->GetPointData()->Initialize();
  // Every third triangle wound the other way round.
  vtkNew<vtkCellArray> mixed;
  vtkNew<vtkIdList> ids;
  for (vtkIdType k = 0; k < sphere->GetNumberOfPolys(); ++k)
  {
    sphere->GetPolys()->GetCellAtId(k, ids);
    if (k % 3 == 0)
    {
      std::swap(ids->GetPointer(0)[0], ids->GetPointer(0)[1]);
    }
    mixed->InsertNextCell(ids);
  }
  sphere->SetPolys(mixed);
  vtkSmartPointer<vtkPolyData> output = withNormals(sphere);
  double worst = 1;
  for (vtkIdType i = 0; i < output->GetNumberOfPoints(); ++i)
  {
    double p[3], n[3];
    output->GetPoint(i, p);
    output->GetPointData()->GetNormals()->GetTuple(i, n);
    worst = std::min(worst, (p[0] * n[0] + p[1] * n[1] + p[2] * n[2]) / 0.5); // radius 0.5
  }
  EXPECT_GT(worst, 0.98);
  const std::string report = reportOf(output);
  EXPECT_NE(report.find(", after turning round the polygons wound against their neighbours ("), std::string::npos)
    << report;
}

TEST(ShadingNormals, CopiesThatDifferInTheirLastDigitsWeldUnderATolerance)
{
  // A ridge whose second triangle's copies of the ridge points sit 1e-9 away.
  vtkNew<vtkPoints> points;
  for (const Position& p : std::vector<Position>{
         { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, -0.3 }, { 1e-9, 0, 0 }, { 1 + 1e-9, 0, 0 }, { 0, -1, -0.3 } })
  {
    points->InsertNextPoint(p.data());
  }
  vtkNew<vtkCellArray> triangles;
  const vtkIdType first[3] = { 0, 1, 2 }, second[3] = { 4, 3, 5 };
  triangles->InsertNextCell(3, first);
  triangles->InsertNextCell(3, second);
  vtkNew<vtkPolyData> ridge;
  ridge->SetPoints(points);
  ridge->SetPolys(triangles);
  vtkNew<vtkShadingNormalsFilter> filter;
  filter->SetInputData(ridge);
  filter->Update();
  double n0[3], n3[3];
  filter->GetOutput()->GetPointData()->GetNormals()->GetTuple(0, n0);
  EXPECT_GT(n0[1], 0.2); // its own triangle's normal, leaning to +y
  filter->SetWeldTolerance(1e-6);
  filter->Update();
  filter->GetOutput()->GetPointData()->GetNormals()->GetTuple(0, n0);
  filter->GetOutput()->GetPointData()->GetNormals()->GetTuple(3, n3);
  EXPECT_NEAR(n0[1], 0.0, 1e-7); // the ridge's normal, straight up
  EXPECT_NEAR(n0[2], 1.0, 1e-7);
  EXPECT_EQ(Position({ n0[0], n0[1], n0[2] }), Position({ n3[0], n3[1], n3[2] }));
}

TEST(ShadingNormals, AnEmptyMeshGivesAnEmptyOutput)
{
  vtkNew<vtkPolyData> empty;
  vtkNew<vtkShadingNormalsFilter> filter;
  filter->SetInputData(empty);
  filter->Update();
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 0);
  EXPECT_EQ(filter->GetReport(), "");
}
}
