// The filter as a VTK user meets it: normals, pass-through of input arrays, errors, thread
// count, files, and a golden regression on the Stanford bunny.
#include "ArrayComparison.h"
#include "FilterRun.h"
#include "MeshFiles.h"
#include "TestMeshes.h"
#include "VtkErrorCapture.h"

#include "SceneFile.h"
#include "vtkLocalReflectanceFilter.h"
#include "vtkShadingNormalsFilter.h"

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCellData.h"
#include "vtkFloatArray.h"
#include "vtkIntArray.h"
#include "vtkPlaneSource.h"
#include "vtkReverseSense.h"
#include "vtkSMPTools.h"
#include "vtkStringArray.h"
#include "vtkXMLPolyDataReader.h"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>

namespace
{
using namespace shadelab;
using shadelab::testing::shadeWithFilter;

/// A distant light straight down -z, lighting the sphere's top, viewer on +z.
Scene overheadLight()
{
  Scene scene;
  scene.viewer.viewDirection = { 0, 0, -1 };
  scene.lights = { { "sun", DistantLight{ { 0, 0, -1 }, Rgb(1.0), 1.0, false } },
    { "lamp", PointLight{ { 0.5, 0.5, 3.0 }, Rgb(1.0), 4.0, Attenuation{} } },
    { "sky", AmbientLight{ Rgb(0.5, 0.6, 1.0), 0.2 } } };
  return scene;
}

/// The filter's output in its default precision, float32.
vtkSmartPointer<vtkPolyData> run(
  vtkPolyData* input, const Scene& scene, const std::vector<std::string>& arrays = { "default" }, bool orient = true)
{
  return shadeWithFilter(input, scene, arrays, vtkAlgorithm::SINGLE_PRECISION, orient);
}

std::string normalsReport(vtkPolyData* output)
{
  return vtkStringArray::SafeDownCast(output->GetFieldData()->GetAbstractArray("shadelab_normals"))->GetValue(0);
}

vtkSmartPointer<vtkPolyData> sphereWithoutNormals(bool woundInward)
{
  vtkSmartPointer<vtkPolyData> sphere = shadelab::testing::exactSphere(40);
  sphere->GetPointData()->SetNormals(nullptr);
  if (!woundInward)
  {
    return sphere;
  }
  vtkNew<vtkReverseSense> reverse;
  reverse->SetInputData(sphere);
  reverse->ReverseCellsOn();
  reverse->Update();
  return reverse->GetOutput();
}

/// Calls visit(ids) for each triangle of a triangle mesh.
template<typename Visit>
void forEachTriangle(vtkPolyData* mesh, Visit&& visit)
{
  auto cells = vtk::TakeSmartPointer(mesh->GetPolys()->NewIterator());
  for (cells->GoToFirstCell(); !cells->IsDoneWithTraversal(); cells->GoToNextCell())
  {
    vtkIdType size;
    const vtkIdType* ids;
    cells->GetCurrentCell(size, ids);
    if (size == 3)
    {
      visit(ids);
    }
  }
}

/// The smallest n.(p - centre) over the vertices: > 0 when every normal points outward.
double smallestOutwardness(vtkPolyData* mesh, vtkDataArray* normals)
{
  double smallest = 1e300;
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    double p[3], n[3];
    mesh->GetPoint(i, p);
    normals->GetTuple(i, n);
    smallest = std::min(smallest, n[0] * p[0] + n[1] * p[1] + n[2] * p[2]);
  }
  return smallest;
}

TEST(Normals, ComputedWithoutSplittingAndTurnedOutward)
{
  vtkSmartPointer<vtkPolyData> inward = sphereWithoutNormals(true);
  vtkSmartPointer<vtkPolyData> output = run(inward, overheadLight());
  EXPECT_EQ(output->GetNumberOfPoints(), inward->GetNumberOfPoints());
  vtkDataArray* normals = output->GetPointData()->GetNormals();
  ASSERT_NE(normals, nullptr);
  EXPECT_STREQ(normals->GetName(), "Normals");
  EXPECT_GT(smallestOutwardness(output, normals), 0.99);
  const std::string report = normalsReport(output);
  EXPECT_NE(report.find("The mesh has no point normals: computed area-weighted ones"), std::string::npos) << report;
  EXPECT_NE(report.find("They point into the mesh"), std::string::npos) << report;
  EXPECT_NE(report.find("; flipped them outward."), std::string::npos) << report;
}

TEST(Normals, OutwardWindingNeedsNoFlip)
{
  vtkSmartPointer<vtkPolyData> output = run(sphereWithoutNormals(false), overheadLight());
  EXPECT_GT(smallestOutwardness(output, output->GetPointData()->GetNormals()), 0.99);
  EXPECT_EQ(
    normalsReport(output), "The mesh has no point normals: computed area-weighted ones and added them as 'Normals'.");
}

TEST(Normals, OrientationCanBeLeftAlone)
{
  vtkSmartPointer<vtkPolyData> output = run(sphereWithoutNormals(true), overheadLight(), { "default" }, false);
  EXPECT_LT(smallestOutwardness(output, output->GetPointData()->GetNormals()), -0.99);
  const std::string report = normalsReport(output);
  EXPECT_NE(report.find("; kept as they are, because orienting them outward is off."), std::string::npos) << report;
}

TEST(Normals, InwardInputNormalsAreUsedFlippedButPassThroughUnchanged)
{
  vtkSmartPointer<vtkPolyData> sphere = shadelab::testing::exactSphere(40);
  vtkDataArray* normals = sphere->GetPointData()->GetNormals();
  for (vtkIdType i = 0; i < normals->GetNumberOfTuples(); ++i)
  {
    double n[3];
    normals->GetTuple(i, n);
    normals->SetTuple3(i, -n[0], -n[1], -n[2]);
  }
  vtkSmartPointer<vtkPolyData> output = run(sphere, overheadLight(), { "sun_cos_incidence" });
  EXPECT_EQ(output->GetPointData()->GetNormals(), normals); // the same array, untouched
  EXPECT_LT(smallestOutwardness(output, normals), -0.99);
  vtkDataArray* cosine = output->GetPointData()->GetArray("sun_cos_incidence");
  EXPECT_DOUBLE_EQ(cosine->GetComponent(0, 0), 1.0); // vertex 0 is the top of the sphere
  EXPECT_NE(normalsReport(output).find(
              "; flipped them outward. Shaded with the flipped copy; the input's array passes through unchanged."),
    std::string::npos);
}

TEST(Normals, OpenSheetIsNeverFlipped)
{
  vtkNew<vtkPlaneSource> plane; // normals +z
  plane->SetResolution(10, 10);
  plane->Update();
  vtkSmartPointer<vtkPolyData> output = run(plane->GetOutput(), overheadLight(), { "sun_cos_incidence" });
  EXPECT_EQ(normalsReport(output), "Using the mesh's point normals 'Normals'.");
  EXPECT_DOUBLE_EQ(output->GetPointData()->GetArray("sun_cos_incidence")->GetComponent(0, 0), 1.0);
}

TEST(Normals, PreparedOnceAndRedoneWhenTheirInputsChange)
{
  vtkSmartPointer<vtkPolyData> mesh = sphereWithoutNormals(true);
  vtkNew<vtkLocalReflectanceFilter> filter;
  filter->SetInputData(mesh);
  filter->SetScene(overheadLight());
  filter->Update();
  vtkDataArray* first = filter->GetOutput()->GetPointData()->GetNormals();
  EXPECT_GT(smallestOutwardness(filter->GetOutput(), first), 0.99);

  // A new run on the same input (new lights, say) reuses the prepared normals.
  filter->SetScene(overheadLight());
  filter->Update();
  EXPECT_EQ(filter->GetOutput()->GetPointData()->GetNormals(), first);

  // Orientation off: prepared again, and inward.
  filter->OrientNormalsOutwardOff();
  filter->Update();
  EXPECT_LT(smallestOutwardness(filter->GetOutput(), filter->GetOutput()->GetPointData()->GetNormals()), -0.99);
  filter->OrientNormalsOutwardOn();

  // A change of the input itself: its triangles wound the other way round give outward
  // normals that need no flip, and the report says so.
  vtkNew<vtkReverseSense> reverse;
  reverse->SetInputData(mesh);
  reverse->ReverseCellsOn();
  reverse->Update();
  mesh->DeepCopy(reverse->GetOutput());
  filter->Update();
  EXPECT_EQ(filter->GetNormalsReport(),
    "The mesh has no point normals: computed area-weighted ones and added them as 'Normals'.");

  // A new prefix renames the computed normals.
  filter->SetArrayPrefix("lit_");
  filter->Update();
  vtkDataArray* renamed = filter->GetOutput()->GetPointData()->GetArray("lit_Normals");
  ASSERT_NE(renamed, nullptr);

  // Outputs share the prepared normals: one edited in place (and marked modified) is not
  // trusted again.
  for (vtkIdType i = 0; i < renamed->GetNumberOfTuples(); ++i)
  {
    renamed->SetTuple3(i, 0, 0, 1);
  }
  renamed->Modified();
  filter->SetScene(overheadLight());
  filter->Update();
  EXPECT_GT(
    smallestOutwardness(filter->GetOutput(), filter->GetOutput()->GetPointData()->GetArray("lit_Normals")), 0.99);

  // Another mesh with the same points object, so the same modification time: only the top
  // half of the sphere's triangles, whose normals are not the whole sphere's.
  vtkNew<vtkPolyData> cap;
  cap->SetPoints(mesh->GetPoints());
  vtkNew<vtkCellArray> top;
  forEachTriangle(mesh,
    [&](const vtkIdType* ids)
    {
      if (mesh->GetPoint(ids[0])[2] > 0.5)
      {
        top->InsertNextCell(3, ids);
      }
    });
  cap->SetPolys(top);
  mesh->GetPoints()->Modified(); // now both meshes report the points' time as theirs
  ASSERT_EQ(cap->GetMTime(), mesh->GetMTime());
  filter->Update();          // prepared for the sphere, at that time
  filter->SetInputData(cap); // nothing else changes: only the input's identity tells
  filter->Update();
  vtkNew<vtkLocalReflectanceFilter> fresh;
  fresh->SetInputData(cap);
  fresh->SetScene(overheadLight());
  fresh->SetArrayPrefix("lit_");
  fresh->Update();
  vtkDataArray* cached = filter->GetOutput()->GetPointData()->GetArray("lit_Normals");
  vtkDataArray* recomputed = fresh->GetOutput()->GetPointData()->GetArray("lit_Normals");
  for (vtkIdType i = 0; i < cap->GetNumberOfPoints(); ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      ASSERT_EQ(cached->GetComponent(i, c), recomputed->GetComponent(i, c)) << i;
    }
  }
}

TEST(PassThrough, InputArraysAndAttributesAreUntouched)
{
  vtkSmartPointer<vtkPolyData> sphere = shadelab::testing::exactSphere(20);
  vtkNew<vtkFloatArray> temperature;
  temperature->SetName("temperature");
  temperature->SetNumberOfTuples(sphere->GetNumberOfPoints());
  temperature->FillValue(21.5f);
  sphere->GetPointData()->SetScalars(temperature);
  vtkNew<vtkIntArray> region;
  region->SetName("region");
  region->SetNumberOfTuples(sphere->GetNumberOfCells());
  region->FillValue(7);
  sphere->GetCellData()->AddArray(region);

  vtkSmartPointer<vtkPolyData> output = run(sphere, overheadLight(), { "all" });
  EXPECT_EQ(output->GetPointData()->GetScalars(), temperature.Get());
  EXPECT_EQ(output->GetPointData()->GetNormals(), sphere->GetPointData()->GetNormals());
  EXPECT_EQ(output->GetCellData()->GetArray("region"), region.Get());
  EXPECT_EQ(output->GetPoints(), sphere->GetPoints());
  EXPECT_EQ(output->GetPolys(), sphere->GetPolys());
  EXPECT_EQ(temperature->GetValue(5), 21.5f);
}

std::string filterError(
  vtkPolyData* input, const Scene& scene, const std::vector<std::string>& arrays, const std::string& prefix = "")
{
  vtkNew<vtkLocalReflectanceFilter> filter;
  vtkNew<app::VtkErrorCapture> errors;
  errors->watch(filter);
  filter->SetInputData(input);
  filter->SetScene(scene);
  filter->SetArraySelection(arrays);
  filter->SetArrayPrefix(prefix);
  filter->Update();
  return errors->message();
}

TEST(FilterErrors, AnEmptyInputGivesAnEmptyOutputAndNoError)
{
  // VTK's convention (vtkElevationFilter's, say): nothing in, nothing out, and a pipeline that
  // goes on. (The command line refuses an empty mesh itself.)
  vtkNew<vtkPolyData> empty;
  EXPECT_EQ(filterError(empty, overheadLight(), { "all" }), "");
  vtkNew<vtkLocalReflectanceFilter> filter;
  filter->SetInputData(empty);
  filter->SetScene(overheadLight());
  filter->Update();
  EXPECT_EQ(filter->GetOutput()->GetNumberOfPoints(), 0);
  EXPECT_EQ(filter->GetOutput()->GetPointData()->GetNumberOfArrays(), 0);
  vtkNew<vtkShadingNormalsFilter> normals;
  normals->SetInputData(empty);
  normals->Update();
  EXPECT_EQ(normals->GetOutput()->GetNumberOfPoints(), 0);
  EXPECT_EQ(normals->GetReport(), "");
}

TEST(FilterErrors, ExactMessages)
{

  vtkNew<vtkPolyData> cloud;
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> vertices;
  for (int i = 0; i < 3; ++i)
  {
    vertices->InsertNextCell(1);
    vertices->InsertCellPoint(points->InsertNextPoint(i, 0, 0));
  }
  cloud->SetPoints(points);
  cloud->SetVerts(vertices);
  EXPECT_EQ(filterError(cloud, overheadLight(), { "default" }),
    "the mesh has no polygons (3 vertex or line cells): surface shading needs a surface");

  vtkSmartPointer<vtkPolyData> sphere = shadelab::testing::exactSphere(10);
  Scene bad = overheadLight();
  std::get<PointLight>(bad.lights[1].source).intensity = -1;
  EXPECT_EQ(filterError(sphere, bad, { "default" }), "scene /lights/1/intensity: must be a number >= 0");

  const std::string unknown = filterError(sphere, overheadLight(), { "total", "bogus" });
  EXPECT_EQ(unknown.substr(0, unknown.find(':')), "unknown array 'bogus'; this scene has");

  vtkNew<vtkFloatArray> clash;
  clash->SetName("total");
  clash->SetNumberOfTuples(sphere->GetNumberOfPoints());
  sphere->GetPointData()->AddArray(clash);
  EXPECT_EQ(filterError(sphere, overheadLight(), { "default" }),
    "the input already has a point array named 'total', which this filter would write: set an "
    "array prefix (shadelab shade --prefix) to keep both");
  EXPECT_EQ(filterError(sphere, overheadLight(), { "default" }, "shade_"), "");
}

TEST(FilterErrors, CorruptOrOutOfRangeInput)
{
  // A triangle that names a point the mesh does not have (vtkPolyDataReader does not check).
  vtkNew<vtkPolyData> corrupt;
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(0, 0, 0);
  points->InsertNextPoint(1, 0, 0);
  points->InsertNextPoint(0, 1, 0);
  corrupt->SetPoints(points);
  vtkNew<vtkCellArray> triangles;
  const vtkIdType ids[3] = { 0, 1, 2000000 };
  triangles->InsertNextCell(3, ids);
  corrupt->SetPolys(triangles);
  EXPECT_EQ(filterError(corrupt, overheadLight(), { "default" }),
    "the mesh's cells use point id 2000000, but it has 3 points: the mesh is corrupt");

  vtkSmartPointer<vtkPolyData> sphere = shadelab::testing::exactSphere(10);
  vtkNew<vtkFloatArray> shortNormals;
  shortNormals->SetName("Normals");
  shortNormals->SetNumberOfComponents(3);
  shortNormals->SetNumberOfTuples(5);
  sphere->GetPointData()->SetNormals(shortNormals);
  EXPECT_EQ(filterError(sphere, overheadLight(), { "default" }),
    "the point normals 'Normals' have 5 tuples of 3 components: there must be one 3-component "
    "normal per point (" +
      std::to_string(sphere->GetNumberOfPoints()) + ")");
}

TEST(FilterErrors, CoordinatesBeyondThePrecision)
{
  // At 1e20, squared distances overflow float32 (3.4e38): refused there, exact in float64.
  vtkSmartPointer<vtkPolyData> far = shadelab::testing::exactSphere(10, { 1e20, 0, 0 }, 1e19);
  Scene scene;
  scene.viewer.viewDirection = { 0, 0, -1 };
  scene.lights = { { "sun", DistantLight{ { 0, 0, -1 }, Rgb(1.0), 1.0, false } } };
  EXPECT_EQ(filterError(far, scene, { "default" }),
    "the mesh's coordinates reach 1.1e+20, beyond +-2.3e+18 where squared distances overflow "
    "float32: use double precision (shadelab shade --precision float64)");
  vtkNew<vtkLocalReflectanceFilter> filter;
  filter->SetInputData(far);
  filter->SetScene(scene);
  filter->SetArraySelection({ "sun_cos_incidence" });
  filter->SetOutputPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  filter->Update();
  EXPECT_DOUBLE_EQ(filter->GetOutput()->GetPointData()->GetArray("sun_cos_incidence")->GetComponent(0, 0), 1.0);
}

TEST(FilterErrors, ComputedNormalsDoNotReplaceAnArrayNamedNormals)
{
  vtkSmartPointer<vtkPolyData> sphere = sphereWithoutNormals(false);
  vtkNew<vtkFloatArray> notNormals; // an array that happens to be called Normals
  notNormals->SetName("Normals");
  notNormals->SetNumberOfTuples(sphere->GetNumberOfPoints());
  sphere->GetPointData()->AddArray(notNormals);
  EXPECT_EQ(filterError(sphere, overheadLight(), { "default" }),
    "the input already has a point array named 'Normals', which this filter would write: set an "
    "array prefix (shadelab shade --prefix) to keep both");
  EXPECT_EQ(filterError(sphere, overheadLight(), { "default" }, "lit_"), "");
}

using shadelab::testing::expectSamePointArrays;

TEST(Threads, OneAndTwoThreadsGiveTheSameBits)
{
  vtkSmartPointer<vtkPolyData> sphere = shadelab::testing::exactSphere(400); // 160k points
  vtkSmartPointer<vtkPolyData> one, two;
  vtkSMPTools::LocalScope(vtkSMPTools::Config{ 1 }, [&] { one = run(sphere, overheadLight(), { "all" }); });
  vtkSMPTools::LocalScope(vtkSMPTools::Config{ 2 }, [&] { two = run(sphere, overheadLight(), { "all" }); });
  expectSamePointArrays(one, two);
}

TEST(Files, WrittenArraysReadBackBitIdentical)
{
  const std::filesystem::path folder = std::filesystem::temp_directory_path() / "shadelab_roundtrip";
  std::filesystem::create_directories(folder);
  vtkSmartPointer<vtkPolyData> sphere = shadelab::testing::exactSphere(30);
  for (int precision : { vtkAlgorithm::SINGLE_PRECISION, vtkAlgorithm::DOUBLE_PRECISION })
  {
    vtkNew<vtkLocalReflectanceFilter> filter;
    filter->SetInputData(sphere);
    filter->SetScene(overheadLight());
    filter->SetArraySelection({ "all" });
    filter->SetOutputPrecision(precision);
    filter->Update();
    for (const char* extension : { ".vtp", ".vtk" })
    {
      SCOPED_TRACE(std::string(extension) + (precision == vtkAlgorithm::SINGLE_PRECISION ? " float32" : " float64"));
      const std::string file = (folder / (std::string("sphere") + extension)).string();
      app::writeMesh(filter->GetOutput(), file);
      vtkSmartPointer<vtkPolyData> back = app::readMesh(file);
      expectSamePointArrays(filter->GetOutput(), back);
    }
  }
  std::filesystem::remove_all(folder);
}
}
