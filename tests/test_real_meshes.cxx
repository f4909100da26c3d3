// Every bundled mesh, placed and scaled as its file has it, under the default light kit (what
// `shadelab shade MESH -o OUT` uses): finite arrays, one normal per position, normals out of
// the mesh, and a picture a person would call well lit.
#include "FilterRun.h"
#include "MeshFiles.h"
#include "TestPaths.h"

#include "DefaultLightKit.h"
#include "NormalOrientation.h"
#include "SceneFile.h"
#include "SceneFrame.h"
#include "ShadeLabMeshExtent.h"
#include "ShadingFlags.h"

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkDataArray.h"
#include "vtkPointData.h"
#include "vtkPoints.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

namespace
{
using namespace shadelab;

struct MeshCase
{
  const char* file;
  vtkIdType points;
};

class RealMesh : public ::testing::TestWithParam<MeshCase>
{
};

glm::dvec3 tupleOf(vtkDataArray* array, vtkIdType i)
{
  double t[3];
  array->GetTuple(i, t);
  return { t[0], t[1], t[2] };
}

/// Rec. 709 luminance of linear RGB.
double luminance(const glm::dvec3& rgb)
{
  return 0.2126 * rgb.x + 0.7152 * rgb.y + 0.0722 * rgb.z;
}

TEST_P(RealMesh, DefaultLightKitLightsItWell)
{
  const MeshCase meshCase = GetParam();
  vtkSmartPointer<vtkPolyData> mesh = app::readMesh(shadelab::testing::sourcePath("data/meshes/") + meshCase.file);
  ASSERT_EQ(mesh->GetNumberOfPoints(), meshCase.points);
  const Scene kit = defaultLightKit();
  vtkSmartPointer<vtkPolyData> output =
    shadelab::testing::shadeWithFilter(mesh, kit, { "all" }, vtkAlgorithm::SINGLE_PRECISION);
  ASSERT_EQ(output->GetNumberOfPoints(), meshCase.points);

  // Every array finite.
  vtkPointData* pointData = output->GetPointData();
  for (int a = 0; a < pointData->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* array = pointData->GetArray(a);
    for (vtkIdType v = 0; v < array->GetNumberOfValues(); ++v)
    {
      ASSERT_TRUE(std::isfinite(array->GetVariantValue(v).ToDouble())) << array->GetName() << " value " << v;
    }
  }

  // Points at one position have one normal, to the bit.
  vtkDataArray* normals = pointData->GetNormals();
  std::map<std::array<double, 3>, glm::dvec3> normalAt;
  for (vtkIdType i = 0; i < output->GetNumberOfPoints(); ++i)
  {
    std::array<double, 3> p;
    output->GetPoint(i, p.data());
    const auto [entry, isNew] = normalAt.emplace(p, tupleOf(normals, i));
    ASSERT_TRUE(isNew || entry->second == tupleOf(normals, i)) << "point " << i;
  }

  // The normals point out of the mesh: the flux through it is positive (NormalOrientation.h).
  const MeshExtent extent = meshExtentOf(output);
  NormalOrientationAccumulator orientation(extent.centre, extent.radius);
  auto cell = vtk::TakeSmartPointer(output->GetPolys()->NewIterator());
  for (cell->GoToFirstCell(); !cell->IsDoneWithTraversal(); cell->GoToNextCell())
  {
    vtkIdType size;
    const vtkIdType* ids;
    cell->GetCurrentCell(size, ids);
    auto point = [&](vtkIdType id) { return tupleOf(output->GetPoints()->GetData(), id); };
    for (vtkIdType k = 2; k < size; ++k)
    {
      orientation.addTriangle(point(ids[0]), point(ids[k - 1]), point(ids[k]), tupleOf(normals, ids[0]),
        tupleOf(normals, ids[k - 1]), tupleOf(normals, ids[k]));
    }
  }
  EXPECT_GT(orientation.result().flux, 0.0);

  // Well lit, as seen from the kit's viewer: no vertex it sees is dark (luminance below 0.2)
  // or clipped (a channel above 1), the median is a mid grey (0.35 to 0.65), and the shape
  // reads: the 5% brightest and darkest differ by at least 0.15. (Measured: every vertex from
  // 0.23 up, medians 0.41 to 0.50, spreads 0.26 to 0.35.)
  const glm::dvec3 eye = *placedOnMesh(kit, extent).viewer.position;
  vtkDataArray* total = pointData->GetArray("total");
  std::vector<double> seen;
  for (vtkIdType i = 0; i < output->GetNumberOfPoints(); ++i)
  {
    const glm::dvec3 n = tupleOf(normals, i);
    const glm::dvec3 toEye = eye - tupleOf(output->GetPoints()->GetData(), i);
    if (glm::dot(n, toEye) > 0.0)
    {
      const glm::dvec3 rgb = tupleOf(total, i);
      EXPECT_LE(std::max({ rgb.x, rgb.y, rgb.z }), 1.0) << "point " << i;
      seen.push_back(luminance(rgb));
    }
  }
  ASSERT_GT(seen.size(), static_cast<std::size_t>(meshCase.points / 4));
  std::sort(seen.begin(), seen.end());
  auto quantile = [&](double q) { return seen[static_cast<std::size_t>(q * (seen.size() - 1))]; };
  EXPECT_GE(seen.front(), 0.2);
  EXPECT_GE(quantile(0.5), 0.35);
  EXPECT_LE(quantile(0.5), 0.65);
  EXPECT_GE(quantile(0.95) - quantile(0.05), 0.15);
  std::cout << meshCase.file << ": " << seen.size() << " vertices seen, luminance from " << seen.front() << ", median "
            << quantile(0.5) << ", 5-95% spread " << quantile(0.95) - quantile(0.05) << "\n";
}

/// Whether the segment from p, lifted along n above the corners of every triangle around it,
/// to q meets a triangle of the mesh that has no corner at p: Moller and Trumbore's test in
/// double precision, triangle by triangle, sharing no code with the ray casting it checks.
bool blockedByAnotherTriangle(vtkPolyData* mesh, const glm::dvec3& p, const glm::dvec3& n, const glm::dvec3& q)
{
  double lift = 0;
  {
    auto cell = vtk::TakeSmartPointer(mesh->GetPolys()->NewIterator());
    for (cell->GoToFirstCell(); !cell->IsDoneWithTraversal(); cell->GoToNextCell())
    {
      vtkIdType size;
      const vtkIdType* ids;
      cell->GetCurrentCell(size, ids);
      bool own = false;
      double rise = 0;
      for (vtkIdType k = 0; k < size; ++k)
      {
        const glm::dvec3 corner = tupleOf(mesh->GetPoints()->GetData(), ids[k]);
        own = own || corner == p;
        rise = std::max(rise, glm::dot(corner - p, n));
      }
      lift = own ? std::max(lift, rise) : lift;
    }
  }
  const glm::dvec3 start = p + lift * n;
  const glm::dvec3 d = q - start;
  auto cell = vtk::TakeSmartPointer(mesh->GetPolys()->NewIterator());
  for (cell->GoToFirstCell(); !cell->IsDoneWithTraversal(); cell->GoToNextCell())
  {
    vtkIdType size;
    const vtkIdType* ids;
    cell->GetCurrentCell(size, ids);
    auto point = [&](vtkIdType id) { return tupleOf(mesh->GetPoints()->GetData(), id); };
    bool own = false;
    for (vtkIdType k = 0; k < size; ++k)
    {
      own = own || point(ids[k]) == p;
    }
    for (vtkIdType k = 2; k < size && !own; ++k)
    {
      const glm::dvec3 a = point(ids[0]), e1 = point(ids[k - 1]) - a, e2 = point(ids[k]) - a;
      const glm::dvec3 h = glm::cross(d, e2);
      const double det = glm::dot(e1, h);
      if (std::abs(det) < 1e-300)
      {
        continue;
      }
      const glm::dvec3 s = start - a;
      const double u = glm::dot(s, h) / det;
      const glm::dvec3 qv = glm::cross(s, e1);
      const double v = glm::dot(d, qv) / det, t = glm::dot(e2, qv) / det;
      if (u >= 0 && v >= 0 && u + v <= 1 && t > 1e-9 && t < 1)
      {
        return true;
      }
    }
  }
  return false;
}

TEST_P(RealMesh, APointLightsShadowDarkensNoVertexByItsOwnTrianglesAlone)
{
  // The shadow terminator: by default a light that the normal faces is not hidden by the
  // vertex's own facets (docs/formulas.md section 20). Every vertex that the light's shadow
  // darkens, where its first hit was one of its own triangles (flag 64), must be blocked by
  // another triangle too, as an independent test finds from the vertex lifted above its own
  // facets. (With "self_shadowing": "facets", 64 of the bunny's vertices are not, 20 of spot's,
  // 5 of the teapot's, 9 of the owl's and 642 of the dragon's.)
  const MeshCase meshCase = GetParam();
  vtkSmartPointer<vtkPolyData> mesh = app::readMesh(shadelab::testing::sourcePath("data/meshes/") + meshCase.file);
  const Scene scene = parseScene(R"({ "frame": "mesh", "viewer": { "position": [0, 0, 5] }, "lights": [
    { "name": "lamp", "type": "point", "position": [1.5, 2.5, 2], "shadows": true } ] })",
    "lamp.json");
  vtkSmartPointer<vtkPolyData> output =
    shadelab::testing::shadeWithFilter(mesh, scene, { "all" }, vtkAlgorithm::SINGLE_PRECISION);
  const glm::dvec3 lamp = std::get<PointLight>(placedOnMesh(scene, meshExtentOf(output)).lights[0].source).position;
  vtkDataArray* visibility = output->GetPointData()->GetArray("lamp_visibility");
  vtkDataArray* flags = output->GetPointData()->GetArray("shading_flags");
  ASSERT_NE(visibility, nullptr);
  int flagged = 0, darkenedByOwnTrianglesAlone = 0;
  for (vtkIdType i = 0; i < output->GetNumberOfPoints(); ++i)
  {
    if ((int(flags->GetComponent(i, 0)) & FlagHiddenByOwnTriangle) == 0)
    {
      continue;
    }
    ++flagged;
    const glm::dvec3 p = tupleOf(output->GetPoints()->GetData(), i);
    if (visibility->GetComponent(i, 0) == 0 &&
      !blockedByAnotherTriangle(output, p, tupleOf(output->GetPointData()->GetNormals(), i), lamp))
    {
      ++darkenedByOwnTrianglesAlone;
    }
  }
  EXPECT_EQ(darkenedByOwnTrianglesAlone, 0);
  std::cout << meshCase.file << ": " << flagged << " vertices whose first hit is their own triangle\n";
}

TEST(MeshFrame, AScenePlacedOnTheMeshLightsItAlikeAnywhereAtAnySize)
{
  // The bunny as it comes, and moved to x = 1e3 and made 40 times larger (the size and place
  // of a CAD part in millimetres), under studio_mesh.json: the same totals at every vertex.
  vtkSmartPointer<vtkPolyData> bunny = app::readMesh(shadelab::testing::sourcePath("data/meshes/bunny_zipper.ply"));
  auto moved = vtkSmartPointer<vtkPolyData>::New();
  moved->DeepCopy(bunny);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  for (vtkIdType i = 0; i < bunny->GetNumberOfPoints(); ++i)
  {
    double p[3];
    bunny->GetPoint(i, p);
    points->InsertNextPoint(1e3 + 40 * p[0], -250 + 40 * p[1], 40 * p[2]);
  }
  moved->SetPoints(points);
  const Scene studio = readSceneFile(shadelab::testing::sourcePath("data/scenes/studio_mesh.json"));
  vtkSmartPointer<vtkPolyData> here = shadelab::testing::shadeWithFilter(bunny, studio, { "totals" });
  vtkSmartPointer<vtkPolyData> there = shadelab::testing::shadeWithFilter(moved, studio, { "totals" });
  vtkDataArray* expected = here->GetPointData()->GetArray("total");
  vtkDataArray* actual = there->GetPointData()->GetArray("total");
  double worst = 0, brightest = 0;
  for (vtkIdType v = 0; v < expected->GetNumberOfValues(); ++v)
  {
    worst = std::max(worst, std::abs(actual->GetVariantValue(v).ToDouble() - expected->GetVariantValue(v).ToDouble()));
    brightest = std::max(brightest, expected->GetVariantValue(v).ToDouble());
  }
  // float64 arithmetic on points moved in float64: what is left is rounding.
  EXPECT_LT(worst, 1e-9);
  EXPECT_GT(brightest, 0.9); // as lit as studio.json lights the bunny in its own coordinates
}

INSTANTIATE_TEST_SUITE_P(BundledMeshes, RealMesh,
  ::testing::Values(MeshCase{ "bunny_zipper.ply", 35947 }, MeshCase{ "spot.obj", 17568 },
    MeshCase{ "teapot.obj", 3644 }, MeshCase{ "owl_scan.vtp", 12442 }, MeshCase{ "xyzrgb_dragon_50k.ply", 50002 }),
  [](const ::testing::TestParamInfo<MeshCase>& info)
  {
    std::string name = info.param.file;
    std::replace_if(
      name.begin(), name.end(), [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); }, '_');
    return name;
  });
}
