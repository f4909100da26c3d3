// Interreflection through the filters (docs/formulas.md section 23): vtkLocalReflectanceFilter
// with a scene's "interreflection" against the closed sphere's closed form, adding kd times the
// indirect irradiance to diffuse and total and nothing where the mesh sees nothing of itself;
// vtkInterreflectionFilter alone; the same bits on any thread count; the scenes refused.
#include "ArrayComparison.h"
#include "FilterRun.h"
#include "TestMeshes.h"

#include "EnvironmentMap.h"
#include "ShadingFlags.h"
#include "VtkErrorCapture.h"
#include "vtkInterreflectionFilter.h"
#include "vtkTransferRelightFilter.h"

#include "vtkAppendPolyData.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkSMPTools.h"
#include "vtkSphereSource.h"
#include "vtkTriangleFilter.h"

#include <OpenImageIO/imageio.h>
#include <glm/gtc/type_ptr.hpp>
#include <gtest/gtest.h>

#include <cmath>

namespace
{
using namespace shadelab;
using shadelab::testing::shadeWithFilter;

/// The exact sphere with its normals turned inward: its inside is the surface to shade.
vtkSmartPointer<vtkPolyData> insideOfSphere(int resolution, double radius)
{
  vtkSmartPointer<vtkPolyData> sphere = shadelab::testing::exactSphere(resolution, glm::dvec3(0.0), radius);
  vtkDataArray* normals = sphere->GetPointData()->GetNormals();
  for (vtkIdType i = 0; i < normals->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      normals->SetComponent(i, c, -normals->GetComponent(i, c));
    }
  }
  return sphere;
}

/// A lamp of intensity `intensity` at the origin, kd = rho, no ambient or specular light.
Scene lampInside(double intensity, double rho, int bounces)
{
  Scene scene;
  scene.material.ka = Rgb(0.0);
  scene.material.kd = Rgb(rho);
  scene.material.ks = Rgb(0.0);
  scene.viewer.position = glm::dvec3(0.0);
  PointLight lamp;
  lamp.position = glm::dvec3(0.0);
  lamp.intensity = intensity;
  scene.lights = { { "lamp", lamp } };
  scene.interreflection = Interreflection{ bounces, { 64, true } };
  return scene;
}

Rgb tupleOf(vtkPolyData* mesh, const char* name, vtkIdType i)
{
  vtkDataArray* array = mesh->GetPointData()->GetArray(name);
  return array ? Rgb(array->GetComponent(i, 0), array->GetComponent(i, 1), array->GetComponent(i, 2)) : Rgb(NAN);
}

// The lecture's "a closed sphere with a lamp inside": each wall vertex is lit directly with
// I / R^2, and every gather ray meets the wall, whose radiosity is uniform, so three bounces add
// (I / R^2)(rho + rho^2 + rho^3) at every vertex; diffuse is the direct term plus kd times it.
TEST(Interreflection, ALampInsideAClosedSphereLightsItsWallsByTheirBounces)
{
  const double radius = 2.0, intensity = 4.0, rho = 0.5;
  vtkSmartPointer<vtkPolyData> sphere = insideOfSphere(40, radius);
  vtkSmartPointer<vtkPolyData> shaded =
    shadeWithFilter(sphere, lampInside(intensity, rho, 3), { "all" }, vtkAlgorithm::DOUBLE_PRECISION, false);
  const double direct = intensity / (radius * radius);
  const double indirect = direct * (rho + rho * rho + rho * rho * rho);
  ASSERT_GT(sphere->GetNumberOfPoints(), 1000);
  for (vtkIdType i = 0; i < sphere->GetNumberOfPoints(); ++i)
  {
    ASSERT_NEAR(tupleOf(shaded, "indirect_irradiance", i).g, indirect, 1e-9 * indirect) << i;
    ASSERT_NEAR(tupleOf(shaded, "indirect_bounce_2", i).r, direct * rho * rho, 1e-9 * indirect) << i;
    ASSERT_NEAR(tupleOf(shaded, "indirect", i).b, rho * indirect, 1e-9 * indirect) << i;
    ASSERT_NEAR(tupleOf(shaded, "diffuse", i).r, rho * (direct + indirect), 1e-9 * indirect) << i;
    ASSERT_NEAR(tupleOf(shaded, "total", i).g, rho * (direct + indirect), 1e-9 * indirect) << i;
    ASSERT_NEAR(tupleOf(shaded, "ambient_minus_indirect", i).g, -rho * indirect, 1e-9 * indirect) << i;
    ASSERT_LT(tupleOf(shaded, "indirect_irradiance_std_error", i).g, 1e-9 * indirect) << i;
  }
}

// Seen from outside, the sphere meets nothing of itself: indirect 0, and diffuse and total the
// bits of a run without interreflection.
TEST(Interreflection, AConvexMeshSeenFromOutsideKeepsItsBits)
{
  vtkSmartPointer<vtkPolyData> sphere = shadelab::testing::exactSphere(30);
  Scene scene = lampInside(1.0, 0.7, 2);
  scene.lights[0].source = PointLight{};
  std::get<PointLight>(scene.lights[0].source).position = glm::dvec3(3, 2, 1);
  scene.viewer.position = glm::dvec3(0, 0, 5);
  vtkSmartPointer<vtkPolyData> with = shadeWithFilter(sphere, scene, { "default" });
  scene.interreflection.reset();
  vtkSmartPointer<vtkPolyData> without = shadeWithFilter(sphere, scene, { "default" });
  for (const char* name : { "diffuse", "total", "ambient", "specular" })
  {
    shadelab::testing::expectSameBits(
      without->GetPointData()->GetArray(name), with->GetPointData()->GetArray(name), name);
  }
  for (vtkIdType i = 0; i < sphere->GetNumberOfPoints(); ++i)
  {
    ASSERT_EQ(tupleOf(with, "indirect_irradiance", i), Rgb(0.0));
  }
  EXPECT_EQ(without->GetPointData()->GetArray("indirect_irradiance"), nullptr);
}

/// A sphere of radius 0.5 at height 0.6 over a square floor: the floor lights the sphere's
/// underside and the sphere the floor around its shadow.
vtkSmartPointer<vtkPolyData> sphereOverFloor()
{
  return shadelab::testing::sphereOverSquare(40, 40, { 0, 0, 0.6 }, 0.5);
}

// The gather's rays and the sweeps run on the threads in any split: the same bits on one and
// two threads, every array.
TEST(Interreflection, TheSameBitsOnOneAndTwoThreads)
{
  vtkSmartPointer<vtkPolyData> mesh = sphereOverFloor();
  Scene scene = lampInside(3.0, 0.8, 2);
  std::get<PointLight>(scene.lights[0].source).position = glm::dvec3(0.5, 0.3, 2.5);
  scene.lights[0].shadows = true;
  scene.viewer.position = glm::dvec3(0, -4, 3);
  vtkSmartPointer<vtkPolyData> one, two;
  vtkSMPTools::LocalScope(vtkSMPTools::Config{ 1 }, [&] { one = shadeWithFilter(mesh, scene, { "all" }); });
  vtkSMPTools::LocalScope(vtkSMPTools::Config{ 2 }, [&] { two = shadeWithFilter(mesh, scene, { "all" }); });
  shadelab::testing::expectSamePointArrays(one, two);
  // The floor beside the sphere gains light from it; the sphere's underside from the floor.
  double gained = 0;
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    gained += tupleOf(one, "indirect", i).r;
  }
  EXPECT_GT(gained, 1.0);
}

// The lamp in the sphere again, but its normals point out, as most meshes' do, and the
// material is two-sided: the viewer inside sees each wall's back, which gathers on its own side
// and reads the other walls' backs. It gathers what the sphere with inward normals gathers, bit
// for bit (the same rays, turned round with the normals), here with the lamp off the centre so
// that every wall's light differs. From outside, the walls the viewer sees get nothing, though
// their hidden sides are lit.
TEST(Interreflection, ATwoSidedSphereWhoseNormalsPointOutGathersOnTheSideItIsSeenFrom)
{
  vtkSmartPointer<vtkPolyData> outward = shadelab::testing::exactSphere(30, glm::dvec3(0.0), 1.0);
  Scene scene = lampInside(2.0, 0.6, 3);
  std::get<PointLight>(scene.lights[0].source).position = glm::dvec3(0.2, -0.3, 0.1);
  const std::vector<std::string> arrays{ "diffuse", "indirect_irradiance", "indirect_irradiance_std_error",
    "indirect_bounce_2", "shading_flags" };
  vtkSmartPointer<vtkPolyData> inwardShaded =
    shadeWithFilter(insideOfSphere(30, 1.0), scene, arrays, vtkAlgorithm::DOUBLE_PRECISION, false);
  scene.material.twoSided = true;
  vtkSmartPointer<vtkPolyData> seenInside =
    shadeWithFilter(outward, scene, arrays, vtkAlgorithm::DOUBLE_PRECISION, false);
  for (const char* name : { "diffuse", "indirect_irradiance", "indirect_irradiance_std_error", "indirect_bounce_2" })
  {
    shadelab::testing::expectSameBits(
      inwardShaded->GetPointData()->GetArray(name), seenInside->GetPointData()->GetArray(name), name);
  }
  vtkDataArray* flags = seenInside->GetPointData()->GetArray("shading_flags");
  for (vtkIdType i = 0; i < outward->GetNumberOfPoints(); ++i)
  {
    ASSERT_EQ(int(flags->GetComponent(i, 0)) & FlagNormalFlipped, FlagNormalFlipped) << i;
  }
  EXPECT_GT(tupleOf(seenInside, "indirect_irradiance", 0).r, 0.5);

  scene.viewer.position = glm::dvec3(0, 0, 5);
  vtkSmartPointer<vtkPolyData> seenOutside =
    shadeWithFilter(outward, scene, arrays, vtkAlgorithm::DOUBLE_PRECISION, false);
  for (vtkIdType i = 0; i < outward->GetNumberOfPoints(); ++i)
  {
    const bool seenFromOutside =
      (int(seenOutside->GetPointData()->GetArray("shading_flags")->GetComponent(i, 0)) & FlagNormalFlipped) == 0;
    // The walls turned away from the camera are seen from inside (their backs, flipped).
    const Rgb expected = seenFromOutside ? Rgb(0.0) : tupleOf(seenInside, "indirect_irradiance", i);
    ASSERT_EQ(tupleOf(seenOutside, "indirect_irradiance", i), expected) << i;
    ASSERT_EQ(tupleOf(seenOutside, "diffuse", i), seenFromOutside ? Rgb(0.0) : tupleOf(seenInside, "diffuse", i)) << i;
  }
}

/// Two squares of side 2 facing +z, one at z = 0 over the other at z = 1, each cells x cells;
/// the upper one's normals turned down where asked.
vtkSmartPointer<vtkPolyData> twoSquares(int cells, bool upperFacesDown)
{
  vtkNew<vtkAppendPolyData> both;
  for (const double z : { 0.0, 1.0 })
  {
    vtkNew<vtkPlaneSource> square;
    square->SetOrigin(-1, -1, z);
    square->SetPoint1(1, -1, z);
    square->SetPoint2(-1, 1, z);
    square->SetResolution(cells, cells);
    vtkNew<vtkTriangleFilter> triangles;
    triangles->SetInputConnection(square->GetOutputPort());
    triangles->Update();
    auto part = vtkSmartPointer<vtkPolyData>::New();
    part->DeepCopy(triangles->GetOutput());
    vtkDataArray* normals = part->GetPointData()->GetNormals();
    for (vtkIdType i = 0; z > 0 && upperFacesDown && i < normals->GetNumberOfTuples(); ++i)
    {
      normals->SetTuple3(i, 0, 0, -1);
    }
    both->AddInputData(part);
  }
  both->Update();
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->ShallowCopy(both->GetOutput());
  return mesh;
}

/// On twoSquares' mesh: `shaded`'s arrays equal `reference`'s, bit for bit, at the lower square,
/// and are 0 at the upper one, whose top the camera above sees and which gathers nothing there;
/// `gathered` is the lower square's mean red indirect irradiance.
void expectTheLowerSquaresBounces(
  vtkPolyData* shaded, vtkPolyData* reference, const std::vector<std::string>& names, double& gathered)
{
  const vtkIdType lower = shaded->GetNumberOfPoints() / 2;
  double sum = 0;
  for (vtkIdType i = 0; i < shaded->GetNumberOfPoints(); ++i)
  {
    for (const std::string& name : names)
    {
      const Rgb expected = i < lower ? tupleOf(reference, name.c_str(), i) : Rgb(0.0);
      ASSERT_EQ(tupleOf(shaded, name.c_str(), i), expected) << name << " " << i;
    }
    sum += i < lower ? tupleOf(shaded, "indirect_irradiance", i).r : 0.0;
  }
  gathered = sum / double(lower);
}

// A lamp between two squares, the camera above both: it sees the lower square's top and the
// upper one's top, whose underside, lit by the lamp, is hidden from it. Two-sided, that hidden
// side sends its light down to the lower square as a one-sided upper square facing down does,
// bit for bit at the lower square over three bounces; the upper square's top, seen, gathers
// nothing.
TEST(Interreflection, TheHiddenSideOfATwoSidedSurfaceLightsWhatItFaces)
{
  Scene scene = lampInside(1.0, 0.7, 3);
  std::get<PointLight>(scene.lights[0].source).position = glm::dvec3(0.3, 0.1, 0.5);
  scene.viewer.position = glm::dvec3(0.5, 0.2, 4);
  const std::vector<std::string> arrays{ "diffuse", "indirect_irradiance", "indirect_bounce_3" };
  vtkSmartPointer<vtkPolyData> facingDown =
    shadeWithFilter(twoSquares(24, true), scene, arrays, vtkAlgorithm::DOUBLE_PRECISION, false);
  scene.material.twoSided = true;
  vtkSmartPointer<vtkPolyData> mesh = twoSquares(24, false);
  vtkSmartPointer<vtkPolyData> twoSided = shadeWithFilter(mesh, scene, arrays, vtkAlgorithm::DOUBLE_PRECISION, false);
  double gathered = 0;
  ASSERT_NO_FATAL_FAILURE(
    expectTheLowerSquaresBounces(twoSided, facingDown, { "indirect_irradiance", "indirect_bounce_3" }, gathered));
  EXPECT_GT(gathered, 0.05);
}

// VTK's renderer lights both sides of every polygon, so the vtk model gathers on both sides
// with no "two_sided" in the material: the two squares again, whichever way the upper one's
// normals point, its lit underside (hidden from the camera above) lights the lower square, the
// same bits both ways, and its seen top gathers nothing.
TEST(Interreflection, TheVtkModelGathersOnBothSidesAsVtkLightsThem)
{
  Scene scene = lampInside(1.0, 0.7, 2);
  scene.model = ShadingModel::VtkOpenGL2;
  PointLight& lamp = std::get<PointLight>(scene.lights[0].source);
  lamp.position = glm::dvec3(0.3, 0.1, 0.5);
  lamp.attenuation = Attenuation{ AttenuationModel::ConstantLinearQuadratic, 0.0, 0.0, 1.0 }; // vtkLight's 1/d^2
  scene.viewer.position = glm::dvec3(0.5, 0.2, 4);
  const std::vector<std::string> arrays{ "indirect_irradiance", "indirect_bounce_2" };
  vtkSmartPointer<vtkPolyData> facingDown =
    shadeWithFilter(twoSquares(24, true), scene, arrays, vtkAlgorithm::DOUBLE_PRECISION, false);
  vtkSmartPointer<vtkPolyData> mesh = twoSquares(24, false);
  vtkSmartPointer<vtkPolyData> facingUp = shadeWithFilter(mesh, scene, arrays, vtkAlgorithm::DOUBLE_PRECISION, false);
  double gathered = 0;
  for (const auto& [shaded, other] : { std::pair{ facingUp.Get(), facingDown.Get() }, { facingDown, facingUp } })
  {
    ASSERT_NO_FATAL_FAILURE(expectTheLowerSquaresBounces(shaded, other, arrays, gathered));
  }
  EXPECT_GT(gathered, 0.05);
}

// vtkInterreflectionFilter alone, on any mesh with a radiosity array: the closed sphere's
// closed form with a per-vertex albedo that is red alone (no green or blue to reflect).
TEST(Interreflection, TheFilterAloneGathersFromAnyRadiosityArray)
{
  vtkSmartPointer<vtkPolyData> sphere = insideOfSphere(30, 1.0);
  const vtkIdType points = sphere->GetNumberOfPoints();
  vtkNew<vtkDoubleArray> radiosity, albedo;
  radiosity->SetName("glow");
  radiosity->SetNumberOfComponents(3);
  radiosity->SetNumberOfTuples(points);
  albedo->SetName("paint");
  albedo->SetNumberOfComponents(3);
  albedo->SetNumberOfTuples(points);
  for (vtkIdType i = 0; i < points; ++i)
  {
    radiosity->SetTuple3(i, 2.0, 2.0, 2.0);
    albedo->SetTuple3(i, 0.5, 0.0, 0.0);
  }
  sphere->GetPointData()->AddArray(radiosity);
  sphere->GetPointData()->AddArray(albedo);
  vtkNew<vtkInterreflectionFilter> filter;
  filter->SetInputData(sphere);
  filter->SetRadiosityArrayName("glow");
  filter->SetAlbedoArrayName("paint");
  filter->SetBounces(2);
  filter->SetArrayPrefix("ir_");
  filter->Update();
  vtkPolyData* output = filter->GetOutput();
  ASSERT_NE(output->GetPointData()->GetArray("glow"), nullptr); // passed through
  for (vtkIdType i = 0; i < points; ++i)
  {
    // E_1 = 2 everywhere; B_1 = (1, 0, 0); E_2 = (1, 0, 0).
    const Rgb e = tupleOf(output, "ir_indirect_irradiance", i);
    ASSERT_NEAR(e.r, 3.0, 1e-12) << i;
    ASSERT_NEAR(e.g, 2.0, 1e-12) << i;
    ASSERT_NEAR(e.b, 2.0, 1e-12) << i;
  }
  EXPECT_EQ(filter->GetBackHits(), 0);
  EXPECT_NE(
    filter->GetReport().find("2 bounces from 'glow', 64 gather rays per vertex (16 for the later bounces); 0 of"),
    std::string::npos)
    << filter->GetReport();

  // The albedo in float32 (converted, where float64 is used as it is): the same bits.
  vtkSmartPointer<vtkDataArray> inFloat64 = output->GetPointData()->GetArray("ir_indirect_irradiance");
  vtkNew<vtkFloatArray> paint;
  paint->DeepCopy(albedo);
  sphere->GetPointData()->AddArray(paint);
  filter->Update();
  for (vtkIdType i = 0; i < points; ++i)
  {
    const double* before = inFloat64->GetTuple3(i);
    ASSERT_EQ(tupleOf(filter->GetOutput(), "ir_indirect_irradiance", i), Rgb(before[0], before[1], before[2])) << i;
  }

  filter->SetBounces(0);
  filter->Update();
  EXPECT_EQ(tupleOf(filter->GetOutput(), "ir_indirect_irradiance", 0), Rgb(0.0));
  EXPECT_EQ(filter->GetReport(), "0 bounces: no indirect light");

  // A transfer to carry must have the coefficients of order 2, 3 or 4: 4 (order 1) is refused.
  vtkNew<vtkDoubleArray> bands;
  bands->SetName("short_transfer");
  bands->SetNumberOfComponents(4);
  bands->SetNumberOfTuples(points);
  bands->Fill(1);
  sphere->GetPointData()->AddArray(bands);
  filter->AddTransferArrayName("short_transfer");
  vtkNew<shadelab::app::VtkErrorCapture> errors;
  errors->watch(filter);
  filter->Update();
  EXPECT_EQ(errors->message(),
    "the input has no numeric point array 'short_transfer' of transfer vectors (9, 16 or 25 components: "
    "\"estimator\": \"prt\") to carry through the bounces");
}

// The filter alone on both sides of a surface: a closed sphere whose normals point out, its
// fronts (outside) sending 0 and its backs (inside) 2, with an albedo of 0.5. The backs gather
// the inside's E_1 = 2 and E_2 = 1 on the backs' hits; the fronts see nothing. Every back ray
// meets a back. A transfer vector is carried on both sides from its fronts' and backs' arrays:
// its backs' coefficients of 1 gain 0.5 + 0.25.
TEST(Interreflection, TheFilterAloneGathersOnBothSidesOfASurface)
{
  vtkSmartPointer<vtkPolyData> sphere = shadelab::testing::exactSphere(30, glm::dvec3(0.0), 1.0);
  const vtkIdType points = sphere->GetNumberOfPoints();
  for (const auto& [name, value] : { std::pair<const char*, double>{ "glow", 0.0 }, { "inner_glow", 2.0 } })
  {
    vtkNew<vtkDoubleArray> radiosity;
    radiosity->SetName(name);
    radiosity->SetNumberOfComponents(3);
    radiosity->SetNumberOfTuples(points);
    radiosity->Fill(value);
    sphere->GetPointData()->AddArray(radiosity);
  }
  vtkNew<vtkInterreflectionFilter> filter;
  filter->SetInputData(sphere);
  filter->SetRadiosityArrayName("glow");
  filter->SetBackRadiosityArrayName("inner_glow");
  filter->SetAlbedo(0.5, 0.5, 0.5);
  filter->SetBounces(2);
  filter->KeepBouncesOn();
  filter->Update();
  vtkPolyData* output = filter->GetOutput();
  for (vtkIdType i = 0; i < points; ++i)
  {
    ASSERT_EQ(tupleOf(output, "indirect_irradiance", i), Rgb(0.0)) << i;
    ASSERT_NEAR(tupleOf(output, "indirect_irradiance_back", i).g, 3.0, 1e-12) << i;
    ASSERT_NEAR(tupleOf(output, "indirect_bounce_2_back", i).b, 1.0, 1e-12) << i;
    ASSERT_LT(tupleOf(output, "indirect_irradiance_std_error_back", i).r, 1e-12) << i;
  }
  EXPECT_EQ(filter->GetBackHits(), 64 * points);
  EXPECT_NE(filter->GetReport().find("2 bounces from 'glow' and 'inner_glow', 64 gather rays per vertex on each "
                                     "side (16 for the later bounces); " +
              std::to_string(64 * points) + " of " + std::to_string(128 * points) +
              " rays (50%) met the back of a triangle and carried the backs' radiosity;"),
    std::string::npos)
    << filter->GetReport();

  for (const char* name : { "transfer", "transfer_back" })
  {
    vtkNew<vtkDoubleArray> transfer;
    transfer->SetName(name);
    transfer->SetNumberOfComponents(9);
    transfer->SetNumberOfTuples(points);
    transfer->Fill(1);
    sphere->GetPointData()->AddArray(transfer);
  }
  filter->AddTransferArrayName("transfer");
  filter->Update();
  vtkDataArray* front = filter->GetOutput()->GetPointData()->GetArray("transfer_indirect");
  vtkDataArray* back = filter->GetOutput()->GetPointData()->GetArray("transfer_indirect_back");
  ASSERT_EQ(back->GetNumberOfComponents(), 27);
  for (vtkIdType i = 0; i < points; ++i)
  {
    for (int c = 0; c < 27; ++c)
    {
      ASSERT_EQ(front->GetComponent(i, c), 0.0) << i;
      ASSERT_NEAR(back->GetComponent(i, c), 0.75, 1e-12) << i;
    }
  }
  // With its backs' array of another order, or without it, the transfer is refused.
  vtkNew<vtkDoubleArray> otherOrder;
  otherOrder->SetName("transfer_back");
  otherOrder->SetNumberOfComponents(16);
  otherOrder->SetNumberOfTuples(points);
  otherOrder->Fill(1);
  sphere->GetPointData()->AddArray(otherOrder);
  {
    vtkNew<shadelab::app::VtkErrorCapture> mismatch;
    mismatch->watch(filter);
    filter->Update();
    EXPECT_EQ(mismatch->message(),
      "point array 'transfer_back' has 16 components, and 'transfer' 9: a transfer's "
      "backs need as many coefficients as its fronts");
  }
  sphere->GetPointData()->RemoveArray("transfer_back");
  vtkNew<shadelab::app::VtkErrorCapture> errors;
  errors->watch(filter);
  filter->Update();
  EXPECT_EQ(errors->message(),
    "the input has no numeric point array 'transfer_back' of transfer vectors (9, 16 or 25 components: "
    "\"estimator\": \"prt\") to carry through the bounces");
}

// Under a tolerance, "auto" bounces stop where what the rest can add, max(B_K) rho / (1 - rho),
// fits a tenth of interreflection's half of it. Inside the closed sphere that bound is exact:
// B_K = rho^K B_0 everywhere, B_0 = rho I / R^2 = 0.5, so K = 10 (0.5^11 <= 5e-4 < 0.5^10) and
// the indirect term is the infinite series' rho^2 / (1 - rho) I / R^2 less that rest. Every ray
// meets the same radiosity: no standard error, and the first run's 64 rays are kept.
TEST(Interreflection, AutoBouncesStopWhereTheRestFitsTheTolerance)
{
  const double radius = 2.0, intensity = 4.0, rho = 0.5, tolerance = 0.01;
  vtkSmartPointer<vtkPolyData> sphere = insideOfSphere(40, radius);
  Scene scene = lampInside(intensity, rho, 1);
  scene.interreflection->bouncesFromTolerance = true;
  scene.interreflection->sampling.fromTolerance = true;
  vtkNew<vtkLocalReflectanceFilter> filter;
  filter->SetInputData(sphere);
  filter->SetScene(scene);
  filter->SetArraySelection({ "all" });
  filter->SetOrientNormalsOutward(false);
  filter->SetTolerance(tolerance);
  filter->Update();
  const double direct = intensity / (radius * radius);
  const double rest = std::pow(rho, 11) * direct * rho / (1 - rho);
  const double indirect = rho * rho / (1 - rho) * direct - rest;
  vtkPolyData* shaded = filter->GetOutput();
  for (vtkIdType i = 0; i < sphere->GetNumberOfPoints(); ++i)
  {
    ASSERT_NEAR(tupleOf(shaded, "indirect", i).g, indirect, 1e-6) << i; // float32, which the tolerance chose
  }
  // "all" takes each bounce the plan made, bounce n adding rho^n I / R^2, and none past them.
  for (int n = 1; n <= 10; ++n)
  {
    const double bounce = std::pow(rho, n) * direct;
    EXPECT_NEAR(tupleOf(shaded, ("indirect_bounce_" + std::to_string(n)).c_str(), 0).b, bounce, 1e-5 * bounce) << n;
  }
  EXPECT_FALSE(shaded->GetPointData()->GetArray("indirect_bounce_11"));
  EXPECT_EQ(filter->GetInterreflectionReport().find("asked for"), std::string::npos);
  // One asked for by name past them is not written, and the report says so.
  filter->SetArraySelection({ "indirect", "indirect_bounce_12" });
  filter->Update();
  EXPECT_FALSE(filter->GetOutput()->GetPointData()->GetArray("indirect_bounce_12"));
  const std::string& report = filter->GetInterreflectionReport();
  const std::string note = "; indirect_bounce_12 was asked for, past the 10 bounces the plan made: not written";
  ASSERT_GE(report.size(), note.size());
  EXPECT_EQ(report.substr(report.size() - note.size()), note);
  const InterreflectionChoice& chosen = *filter->GetMethodPlan()->interreflection;
  EXPECT_EQ(chosen.bounces, 10);
  EXPECT_NEAR(chosen.bouncesLeftOut, rest, 1e-6 * rest);
  EXPECT_LE(chosen.bouncesLeftOut, chosen.truncationShare());
  EXPECT_EQ(chosen.samples, 64);
  EXPECT_EQ(chosen.share, tolerance / 2);
  EXPECT_EQ(chosen.directGrowth(), 2.0);
  EXPECT_LE(filter->GetMethodPlan()->predictedError(), tolerance);
  EXPECT_LT(*chosen.estimatedSamplingError, 1e-7); // the float32 direct term's rounding
  EXPECT_EQ(chosen.describeRun().substr(0, 94),
    "interreflection chose 10 bounces (the rest add at most 0.00049) and 64 gather rays per vertex;");

  // Two-sided, with its normals pointing out, the sphere seen from inside gets the same plan and
  // the same bits: the hidden side is shaded under the plan too.
  auto planned = [&](vtkPolyData* mesh, const Scene& shadedScene)
  {
    vtkNew<vtkLocalReflectanceFilter> run;
    run->SetInputData(mesh);
    run->SetScene(shadedScene);
    run->SetArraySelection({ "all" });
    run->SetOrientNormalsOutward(false);
    run->SetTolerance(tolerance);
    run->Update();
    EXPECT_EQ(run->GetMethodPlan()->interreflection->bounces, 10);
    auto output = vtkSmartPointer<vtkPolyData>::New();
    output->DeepCopy(run->GetOutput());
    return output;
  };
  const vtkSmartPointer<vtkPolyData> inward = planned(sphere, scene);
  scene.material.twoSided = true;
  const vtkSmartPointer<vtkPolyData> outward =
    planned(shadelab::testing::exactSphere(40, glm::dvec3(0.0), radius), scene);
  std::vector<std::string> bounceArrays{ "indirect", "indirect_irradiance_std_error" };
  for (int n = 1; n <= 10; ++n)
  {
    bounceArrays.push_back("indirect_bounce_" + std::to_string(n));
  }
  for (const std::string& name : bounceArrays)
  {
    shadelab::testing::expectSameBits(
      inward->GetPointData()->GetArray(name.c_str()), outward->GetPointData()->GetArray(name.c_str()), name.c_str());
  }
}

// The rays are cosine-weighted about the normals' directions, whatever their length: inside a
// bowl of 3/4 of a sphere every point sees the bowl with 3/4 of its cosine-weighted hemisphere,
// so a uniform radiosity of 1 gathers 0.75 (the mean over the vertices, within 1%), with unit
// normals and with normals half as long (which tilted the rays: 0.9 before they were made unit).
TEST(Interreflection, NormalsOfAnyLengthGatherAlike)
{
  vtkNew<vtkSphereSource> source;
  source->SetThetaResolution(64);
  source->SetPhiResolution(32);
  source->SetEndPhi(120);
  source->Update();
  vtkPolyData* bowl = source->GetOutput();
  vtkNew<vtkDoubleArray> radiosity, normals;
  radiosity->SetName("diffuse");
  radiosity->SetNumberOfComponents(3);
  normals->SetNumberOfComponents(3);
  for (vtkIdType i = 0; i < bowl->GetNumberOfPoints(); ++i)
  {
    const glm::dvec3 p = glm::make_vec3(bowl->GetPoint(i));
    radiosity->InsertNextTuple3(1, 1, 1);
    const glm::dvec3 inward = -p / glm::length(p);
    normals->InsertNextTuple3(inward.x, inward.y, inward.z);
  }
  bowl->GetPointData()->AddArray(radiosity);
  for (const double length : { 1.0, 0.5 })
  {
    vtkNew<vtkDoubleArray> scaled;
    scaled->DeepCopy(normals);
    for (vtkIdType v = 0; v < scaled->GetNumberOfValues(); ++v)
    {
      scaled->SetValue(v, length * scaled->GetValue(v));
    }
    bowl->GetPointData()->SetNormals(scaled);
    vtkNew<vtkInterreflectionFilter> filter;
    filter->SetInputData(bowl);
    filter->SetAlbedo(0.5, 0.5, 0.5);
    filter->Update();
    vtkDataArray* gathered = filter->GetOutput()->GetPointData()->GetArray("indirect_irradiance");
    double mean = 0;
    for (vtkIdType i = 0; i < gathered->GetNumberOfTuples(); ++i)
    {
      mean += gathered->GetComponent(i, 0) / double(gathered->GetNumberOfTuples());
    }
    EXPECT_NEAR(mean, 0.75, 0.0075) << "normals of length " << length;
  }
}

// A white-ish closed sphere (kd 0.99) keeps almost all of its light: after the most bounces a
// scene may ask for, 64, the rest can still add 0.99^66 / 0.01 of I / R^2 = 51.5, far above the
// share, and the plan says so rather than pass it off as met. "max_samples" below the first
// run's 64 rays bounds that run too.
TEST(Interreflection, AutoBouncesThatCannotMeetTheShareSaySo)
{
  vtkSmartPointer<vtkPolyData> sphere = insideOfSphere(20, 1.0);
  Scene scene = lampInside(1.0, 0.99, 1);
  scene.interreflection->bouncesFromTolerance = true;
  scene.interreflection->sampling.fromTolerance = true;
  scene.interreflection->sampling.maximum = 16;
  vtkNew<vtkLocalReflectanceFilter> filter;
  filter->SetInputData(sphere);
  filter->SetScene(scene);
  filter->SetOrientNormalsOutward(false);
  filter->SetTolerance(0.01);
  filter->Update();
  const InterreflectionChoice& chosen = *filter->GetMethodPlan()->interreflection;
  EXPECT_EQ(chosen.bounces, 64);
  EXPECT_NEAR(chosen.bouncesLeftOut, std::pow(0.99, 66) / 0.01, 1e-4);
  EXPECT_EQ(chosen.describeRun().substr(0, 126),
    "interreflection chose 64 bounces (the rest add at most 52, above its "
    "share: 64 bounces is the most a scene may ask for) and 16");
  EXPECT_GT(filter->GetMethodPlan()->estimatedError(), 50.0);
}

// What interreflection cannot be given is refused at its field: under a tolerance, fixed counts
// of bounces or rays and an albedo of 1; "auto" without one; an albedo above 1; the spectral mode.
TEST(Interreflection, ScenesItCannotShadeAreRefusedAtTheirField)
{
  vtkSmartPointer<vtkPolyData> sphere = shadelab::testing::exactSphere(12);
  Scene scene = lampInside(1.0, 0.5, 1);
  EXPECT_EQ(shadelab::testing::filterError(sphere, scene, 0.05),
    "scene /interreflection/bounces: a tolerance cannot bound what the bounces past a fixed 1 leave out: give "
    "\"bounces\": \"auto\" (--bounces auto), which takes as many as the tolerance needs; or shade without a "
    "tolerance");
  scene.interreflection->bouncesFromTolerance = true;
  EXPECT_EQ(shadelab::testing::filterError(sphere, scene, 0.05),
    "scene /interreflection/samples: interreflection's gather from a fixed 64 rays per vertex has no error bound "
    "before they are traced: give \"samples\": \"auto\", which chooses the count from the standard errors of a "
    "first run; or shade without a tolerance");
  EXPECT_EQ(shadelab::testing::filterError(sphere, scene),
    "scene /interreflection/bounces: \"auto\" takes interreflection's count of bounces from a tolerance: give one "
    "(shadelab shade --tolerance, the filter's Tolerance), or a number of bounces");
  scene.interreflection->sampling.fromTolerance = true;
  scene.material.kd = Rgb(0.5, 1.0, 0.5);
  EXPECT_EQ(shadelab::testing::filterError(sphere, scene, 0.05),
    "scene /material/kd: kd up to 1: a surface that reflects all the light it receives lets no bounce fade (in a "
    "closed mesh their sum diverges), so a tolerance cannot bound how many are needed: give kd below 1; or shade "
    "without a tolerance and a number of bounces");
  scene.interreflection->bouncesFromTolerance = false;
  scene.interreflection->sampling.fromTolerance = false;
  scene.material.kd = Rgb(1.2, 0.5, 0.5);
  EXPECT_EQ(shadelab::testing::filterError(sphere, scene),
    "scene /material/kd: is the albedo each bounce of \"interreflection\" reflects, and above 1 it reflects more light "
    "than arrives: give components <= 1");
  scene.material.kd = Rgb(0.5);
  scene.interreflection->bounces = 0;
  EXPECT_EQ(shadelab::testing::filterError(sphere, scene),
    "scene /interreflection/bounces: must be a whole number from 1 to 64 (leave \"interreflection\" out for none)");
}

/// An equirectangular .hdr map of 64 x 32 texels, written to the tests' temporary directory,
/// texel (column, row) of radiance radiance(polar angle, azimuth) at its centre; its path.
template<typename Radiance>
std::string mapFile(const std::string& name, Radiance radiance)
{
  const std::string path = ::testing::TempDir() + name + ".hdr";
  const int width = 64, height = 32;
  std::vector<float> pixels;
  for (int row = 0; row < height; ++row)
  {
    for (int column = 0; column < width; ++column)
    {
      const double pi = 3.14159265358979323846;
      const Rgb texel = radiance(pi * (row + 0.5) / height, 2 * pi * (column + 0.5) / width);
      pixels.insert(pixels.end(), { float(texel.r), float(texel.g), float(texel.b) });
    }
  }
  const auto output = OIIO::ImageOutput::create(path);
  EXPECT_TRUE(output && output->open(path, OIIO::ImageSpec(width, height, 3, OIIO::TypeDesc::FLOAT)) &&
    output->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) && output->close())
    << path;
  return path;
}

std::string constantMapFile(const std::string& name, double radiance)
{
  return mapFile(name, [&](double, double) { return Rgb(radiance); });
}

/// A map with "estimator": "prt" of order 2.
NamedLight transferMap(const std::string& file, bool shadows)
{
  EnvironmentLight map;
  map.file = file;
  map.map = std::make_shared<const EnvironmentMap>(readEnvironmentMap(file));
  map.estimator = EnvironmentEstimator::PrecomputedTransfer;
  map.shOrder = 2;
  map.sampling = Sampling{ 32, true };
  NamedLight light{ "sky", map };
  light.shadows = shadows;
  return light;
}

/// The mesh relit under a map file, with or without the indirect transfer.
vtkSmartPointer<vtkPolyData> relit(vtkPolyData* shaded, const std::string& file, double rotation, bool indirect)
{
  vtkNew<vtkTransferRelightFilter> relight;
  relight->SetInputData(shaded);
  relight->SetEnvironmentMapFileName(file);
  relight->SetRotation(rotation);
  relight->SetUseIndirectTransfer(indirect);
  relight->Update();
  auto output = vtkSmartPointer<vtkPolyData>::New();
  output->ShallowCopy(relight->GetOutput());
  return output;
}

// Interreflected transfer (Sloan, Kautz and Snyder 2002): inside the closed sphere under a map
// of radiance 1, without shadows, each wall vertex's transfer is lit by the map with pi L, and
// its bounces add rho + rho^2 + rho^3 of it. Relit under a map of radiance 2 without a ray, the
// mesh gets twice each, 2 pi (1 + rho + rho^2 + rho^3), the indirect part alone 2 pi (rho +
// rho^2 + rho^3), and without its indirect transfer 2 pi, the direct light alone.
TEST(Interreflection, TheTransferCarriedThroughTheBouncesRelightsTheClosedSphere)
{
  const double rho = 0.5;
  vtkSmartPointer<vtkPolyData> sphere = insideOfSphere(30, 2.0);
  Scene scene = lampInside(1.0, rho, 3);
  scene.lights = { transferMap(constantMapFile("radiance_1", 1.0f), false) };
  vtkSmartPointer<vtkPolyData> shaded =
    shadeWithFilter(sphere, scene, { "default", "sky_irradiance" }, vtkAlgorithm::DOUBLE_PRECISION, false);
  ASSERT_EQ(shaded->GetPointData()->GetArray("sky_sh_transfer_indirect")->GetNumberOfComponents(), 27);
  const std::string twice = constantMapFile("radiance_2", 2.0f);
  vtkSmartPointer<vtkPolyData> bounced = relit(shaded, twice, 0, true);
  vtkSmartPointer<vtkPolyData> direct = relit(shaded, twice, 0, false);
  // pi L to the map's quadrature (within 1e-3 of it on 64 x 32 texels); twice the light, twice
  // every term, to rounding.
  const double bounces = rho + rho * rho + rho * rho * rho, pi = 3.14159265358979323846;
  for (vtkIdType i = 0; i < sphere->GetNumberOfPoints(); ++i)
  {
    const Rgb lit = tupleOf(shaded, "sky_irradiance", i), indirect = tupleOf(shaded, "indirect_irradiance", i);
    ASSERT_NEAR(lit.r, pi, 1e-3 * pi) << i;
    ASSERT_NEAR(indirect.g, pi * bounces, 1e-3 * pi) << i;
    ASSERT_NEAR(tupleOf(bounced, "relit_irradiance", i).r, 2 * (lit.r + indirect.r), 1e-9) << i;
    ASSERT_NEAR(tupleOf(bounced, "relit_irradiance_indirect", i).b, 2 * indirect.b, 1e-9) << i;
    ASSERT_NEAR(tupleOf(direct, "relit_irradiance", i).g, 2 * lit.g, 1e-9) << i;
  }
  EXPECT_EQ(direct->GetPointData()->GetArray("relit_irradiance_indirect"), nullptr);

  // Two-sided, the sphere with its normals pointing out carries the transfer through the bounces
  // on the side it is seen from, inside: the bits of the sphere with inward normals.
  scene.material.twoSided = true;
  vtkSmartPointer<vtkPolyData> outward = shadeWithFilter(shadelab::testing::exactSphere(30, glm::dvec3(0.0), 2.0),
    scene, { "default", "sky_irradiance" }, vtkAlgorithm::DOUBLE_PRECISION, false);
  for (const char* name : { "sky_sh_transfer", "sky_sh_transfer_indirect", "indirect_irradiance", "sky_irradiance" })
  {
    shadelab::testing::expectSameBits(
      shaded->GetPointData()->GetArray(name), outward->GetPointData()->GetArray(name), name);
  }

  // An indirect part of the wrong size is refused with what to do.
  vtkNew<vtkDoubleArray> wrong;
  wrong->SetName("sky_sh_transfer_indirect");
  wrong->SetNumberOfComponents(9);
  wrong->SetNumberOfTuples(sphere->GetNumberOfPoints());
  wrong->Fill(0);
  shaded->GetPointData()->AddArray(wrong);
  vtkNew<vtkTransferRelightFilter> relight;
  relight->SetInputData(shaded);
  relight->SetEnvironmentMapFileName(twice);
  vtkNew<shadelab::app::VtkErrorCapture> errors;
  errors->watch(relight);
  relight->Update();
  EXPECT_EQ(errors->message(),
    "point array 'sky_sh_transfer_indirect' is not the indirect part of 'sky_sh_transfer': it must have 3 components "
    "per coefficient, 27, not 9 (or turn UseIndirectTransfer off to relight without it)");
}

// Relighting needs no ray because the bounces are linear in the light: a sphere over a floor,
// shaded with its shadows under one sky and relit under another, gets to rounding the indirect
// irradiance that shading it under the other sky gives (the same rays: "prt" draws them by the
// cosine alone, whatever the map). Both skies are positive and smooth, so that their bands do
// not ring below 0 anywhere: a radiosity below 0 reflects nothing in shading, but all its sign
// in the transfer (a bundled map's bands do ring).
TEST(Interreflection, RelightingUnderAnotherMapGivesItsShadedInterreflection)
{
  const std::string zenith = mapFile("zenith_sky",
    [](double theta, double phi)
    { return Rgb(1 + 0.8 * std::cos(theta), 1 + 0.5 * std::sin(theta) * std::cos(phi), 1 - 0.3 * std::cos(theta)); });
  const std::string side = mapFile("side_sky",
    [](double theta, double phi)
    { return Rgb(0.5 + 0.4 * std::sin(theta) * std::sin(phi), 2 - std::cos(theta), 0.7 + 0.2 * std::cos(2 * theta)); });
  vtkSmartPointer<vtkPolyData> mesh = shadelab::testing::sphereOverSquare(24, 24, { 0, 0, 0.6 }, 0.5);
  Scene scene = lampInside(1.0, 0.8, 2);
  scene.material.kd = Rgb(0.8, 0.6, 0.3);
  scene.viewer.position = glm::dvec3(0, -4, 3);
  scene.lights = { transferMap(side, true) };
  vtkSmartPointer<vtkPolyData> underSide = shadeWithFilter(mesh, scene, { "all" });
  scene.lights = { transferMap(zenith, true) };
  vtkSmartPointer<vtkPolyData> underZenith = shadeWithFilter(mesh, scene, { "all" });
  for (vtkPolyData* run : { underSide.Get(), underZenith.Get() })
  {
    for (int c = 0; c < 3; ++c)
    {
      double range[2];
      run->GetPointData()->GetArray("sky_irradiance")->GetRange(range, c);
      ASSERT_GE(range[0], 0.0) << "the sky's bands ring below 0: this check needs one that does not";
    }
  }
  vtkSmartPointer<vtkPolyData> relitSide = relit(underZenith, side, 0, true);
  double largest = 0;
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    const Rgb expected = tupleOf(underSide, "indirect_irradiance", i);
    const Rgb got = tupleOf(relitSide, "relit_irradiance_indirect", i);
    const Rgb total = tupleOf(relitSide, "relit_irradiance", i);
    for (int c = 0; c < 3; ++c)
    {
      ASSERT_NEAR(got[c], expected[c], 1e-9 * (1 + expected[c])) << i;
      ASSERT_NEAR(total[c], expected[c] + tupleOf(underSide, "sky_irradiance", i)[c], 1e-9 * (1 + total[c])) << i;
    }
    largest = std::max(largest, largestComponent(expected));
  }
  EXPECT_GT(largest, 0.05); // the floor and the sphere light each other
}
}

// The hidden side's transfer bounces too: the two squares under a sky, with shadows, the camera
// above. The upper square's underside, hidden, carries its transfer down to the lower square as
// a one-sided downward square does, bit for bit; the upper square's top, seen, gathers none.
// The mesh's normals are unnamed, as VTK's OBJ importer leaves them.
TEST(Interreflection, TheHiddenSidesTransferLightsWhatItFaces)
{
  Scene scene = lampInside(1.0, 0.7, 2);
  scene.lights = { transferMap(constantMapFile("radiance_1", 1.0f), true) };
  scene.viewer.position = glm::dvec3(0.5, 0.2, 4);
  const std::vector<std::string> arrays{ "sky_sh_transfer_indirect", "indirect_irradiance" };
  vtkSmartPointer<vtkPolyData> facingDown =
    shadeWithFilter(twoSquares(16, true), scene, arrays, vtkAlgorithm::DOUBLE_PRECISION, false);
  scene.material.twoSided = true;
  vtkSmartPointer<vtkPolyData> mesh = twoSquares(16, false);
  mesh->GetPointData()->GetNormals()->SetName(nullptr);
  vtkSmartPointer<vtkPolyData> twoSided = shadeWithFilter(mesh, scene, arrays, vtkAlgorithm::DOUBLE_PRECISION, false);
  vtkDataArray* expected = facingDown->GetPointData()->GetArray("sky_sh_transfer_indirect");
  vtkDataArray* carried = twoSided->GetPointData()->GetArray("sky_sh_transfer_indirect");
  ASSERT_NE(carried, nullptr);
  const vtkIdType lower = mesh->GetNumberOfPoints() / 2;
  double gathered = 0;
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    for (int c = 0; c < carried->GetNumberOfComponents(); ++c)
    {
      ASSERT_EQ(carried->GetComponent(i, c), i < lower ? expected->GetComponent(i, c) : 0.0) << i << " " << c;
    }
    gathered += i < lower ? std::abs(carried->GetComponent(i, 0)) : 0.0;
  }
  EXPECT_GT(gathered / double(lower), 0.05);
}
