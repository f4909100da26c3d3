// Area lights and environment maps through vtkLocalReflectanceFilter: the arrays they add,
// their agreement with the local lights where the two must agree, threads, and errors.
#include "ArrayComparison.h"
#include "EnvironmentLightEstimator.h"
#include "EnvironmentMap.h"
#include "FilterRun.h"
#include "ShadingFlags.h"
#include "TestMeshes.h"
#include "TestPaths.h"
#include "VtkErrorCapture.h"
#include "vtkLocalReflectanceFilter.h"

#include "vtkSMPTools.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

namespace
{
using namespace shadelab;
using shadelab::testing::shadeWithFilter;

Scene shinyScene()
{
  Scene scene;
  scene.viewer.viewDirection = glm::normalize(glm::dvec3(-0.2, -0.3, -1));
  scene.material.kd = { 0.8, 0.5, 0.3 };
  scene.material.ks = { 0.4, 0.4, 0.4 };
  scene.material.shininess = 30;
  return scene;
}

/// A 32x16 map, black but for one texel.
std::shared_ptr<const EnvironmentMap> singleTexelMap(int column, int row, const Rgb& radiance)
{
  auto map = std::make_shared<EnvironmentMap>();
  map->width = 32;
  map->height = 16;
  map->radiance.assign(32 * 16, Rgb(0.0));
  map->radiance[std::size_t(row) * 32 + column] = radiance;
  return map;
}

double largestDifference(vtkDataArray* a, vtkDataArray* b)
{
  double largest = 0;
  for (vtkIdType v = 0; v < a->GetNumberOfValues(); ++v)
  {
    largest = std::max(largest, std::abs(a->GetVariantValue(v).ToDouble() - b->GetVariantValue(v).ToDouble()));
  }
  return largest;
}
}

// docs/formulas.md section 12.3: every texel of a map is a distant light of intensity L Omega from
// the texel's direction; the whole model (diffuse, specular, totals) must agree.
TEST(DistributedLightsFilter, SingleTexelMapIsTheDistantLight)
{
  vtkSmartPointer<vtkPolyData> sphere = shadelab::testing::exactSphere(40);
  const int column = 20, row = 5;
  const Rgb radiance(300, 200, 100);
  EnvironmentLight environment;
  environment.map = singleTexelMap(column, row, radiance);
  environment.estimator = EnvironmentEstimator::BruteForce;
  environment.bruteForceWidth = 32;
  Scene mapped = shinyScene();
  mapped.lights = { { "sky", environment } };

  Scene distant = shinyScene();
  const glm::dvec3 towardTexel = texelCentreDirection(*environment.map, column, row);
  distant.lights = { { "sky", DistantLight{ -towardTexel, radiance * texelSolidAngle(row, 32, 16), 1.0, false } } };

  vtkSmartPointer<vtkPolyData> a = shadeWithFilter(sphere, mapped, { "totals" });
  vtkSmartPointer<vtkPolyData> b = shadeWithFilter(sphere, distant, { "totals" });
  for (const char* name : { "diffuse", "specular", "total" })
  {
    vtkDataArray* fromMap = a->GetPointData()->GetArray(name);
    vtkDataArray* fromLight = b->GetPointData()->GetArray(name);
    EXPECT_LE(largestDifference(fromMap, fromLight), 1e-12 * fromLight->GetRange(-1)[1]) << name;
    EXPECT_GT(fromLight->GetRange(-1)[1], 0.1) << name; // the light does reach the sphere
  }
}

TEST(DistributedLightsFilter, ArraysFollowTheEstimators)
{
  vtkSmartPointer<vtkPolyData> sphere = shadelab::testing::exactSphere(20);
  Scene scene = shinyScene();
  AreaLight panel;
  panel.shape = PolygonEmitter{ { { -1, 3, -1 }, { 1, 3, -1 }, { 1, 3, 1 }, { -1, 3, 1 } } };
  AreaLight bulb;
  bulb.shape = SphereEmitter{ { 2, 2, 2 }, 0.3 };
  bulb.estimator = AreaEstimator::MonteCarlo;
  AreaLight far;
  far.shape = DiskEmitter{ { 0, -9, 0 }, { 0, 1, 0 }, 0.5 };
  far.estimator = AreaEstimator::Point;
  scene.lights = { { "panel", panel }, { "bulb", bulb }, { "far", far } };
  vtkSmartPointer<vtkPolyData> output = shadeWithFilter(sphere, scene, { "all" });
  vtkPointData* arrays = output->GetPointData();

  // Exact E has no error; its Monte Carlo specular has. The point approximation has neither.
  EXPECT_TRUE(arrays->HasArray("panel_irradiance"));
  EXPECT_FALSE(arrays->HasArray("panel_irradiance_std_error"));
  EXPECT_TRUE(arrays->HasArray("panel_specular_std_error"));
  EXPECT_TRUE(arrays->HasArray("bulb_irradiance_std_error"));
  EXPECT_TRUE(arrays->HasArray("bulb_specular_std_error"));
  EXPECT_FALSE(arrays->HasArray("far_irradiance_std_error"));
  EXPECT_FALSE(arrays->HasArray("far_specular_std_error"));
  EXPECT_FALSE(arrays->HasArray("panel_cos_incidence")); // a local light's term

  // diffuse = kd E, and the totals sum the lights.
  vtkDataArray* total = arrays->GetArray("diffuse");
  double largest = 0;
  for (vtkIdType i = 0; i < output->GetNumberOfPoints(); ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      double sum = 0;
      for (const char* light : { "panel", "bulb", "far" })
      {
        const double e = arrays->GetArray((std::string(light) + "_irradiance").c_str())->GetComponent(i, c);
        const double diffuse = arrays->GetArray((std::string(light) + "_diffuse").c_str())->GetComponent(i, c);
        EXPECT_DOUBLE_EQ(diffuse, scene.material.kd[c] * e);
        sum += diffuse;
      }
      EXPECT_NEAR(total->GetComponent(i, c), sum, 1e-12);
      largest = std::max(largest, sum);
    }
  }
  EXPECT_GT(largest, 0.01);
}

TEST(DistributedLightsFilter, OneAndTwoThreadsGiveTheSameBits)
{
  vtkSmartPointer<vtkPolyData> sphere = shadelab::testing::exactSphere(60);
  Scene scene = shinyScene();
  AreaLight disk;
  disk.shape = DiskEmitter{ { 0, 2, 1 }, { 0, -1, -0.5 }, 0.7 };
  disk.estimator = AreaEstimator::MonteCarlo;
  EnvironmentLight environment;
  auto map = std::make_shared<EnvironmentMap>();
  map->width = 16;
  map->height = 8;
  for (int i = 0; i < 16 * 8; ++i)
  {
    map->radiance.push_back(Rgb(1 + i % 7, 1 + i % 5, 1 + i % 3));
  }
  environment.map = map;
  environment.estimator = EnvironmentEstimator::MonteCarlo;
  scene.lights = { { "disk", disk }, { "sky", environment } };
  vtkSmartPointer<vtkPolyData> one, two;
  vtkSMPTools::LocalScope(
    vtkSMPTools::Config{ 1 }, [&] { one = shadeWithFilter(sphere, scene, { "all" }, vtkAlgorithm::SINGLE_PRECISION); });
  vtkSMPTools::LocalScope(
    vtkSMPTools::Config{ 2 }, [&] { two = shadeWithFilter(sphere, scene, { "all" }, vtkAlgorithm::SINGLE_PRECISION); });
  shadelab::testing::expectSamePointArrays(one, two);
}

TEST(DistributedLightsFilter, RefusedWhereTheyCannotApply)
{
  vtkSmartPointer<vtkPolyData> sphere = shadelab::testing::exactSphere(10);
  AreaLight panel;
  panel.shape = SphereEmitter{ { 0, 3, 0 }, 1 };
  auto errorOf = [&](const Scene& scene, double tolerance)
  {
    vtkNew<vtkLocalReflectanceFilter> filter;
    vtkNew<app::VtkErrorCapture> errors;
    errors->watch(filter);
    filter->SetInputData(sphere);
    filter->SetScene(scene);
    filter->SetTolerance(tolerance);
    filter->Update();
    return errors->message();
  };
  Scene vtkModel;
  vtkModel.model = ShadingModel::VtkOpenGL2;
  vtkModel.viewer.position = glm::dvec3(0, 0, 5);
  vtkModel.lights = { { "panel", panel } };
  EXPECT_EQ(errorOf(vtkModel, 0),
    "scene /lights/0/type: VTK's renderer has no area lights or environment maps: use the lecture model");
  Scene lecture = shinyScene();
  lecture.lights = { { "panel", panel } };
  // Its specular integral is sampled, 64 samples: a tolerance needs them drawn to its share.
  EXPECT_EQ(errorOf(lecture, 1e-3),
    "scene /lights/0/samples: a tolerance cannot bound light 'panel' of type \"sphere\": its Monte Carlo estimates "
    "from 64 samples have no "
    "error bound before they are drawn: give it \"samples\": \"auto\", which draws each vertex's samples until "
    "their standard error meets a share of the tolerance; or shade without a tolerance");
  EXPECT_EQ(errorOf(lecture, 0), "");
  std::get<AreaLight>(lecture.lights[0].source).sampling.fromTolerance = true;
  EXPECT_EQ(errorOf(lecture, 1e-3), "");

  // Maps made in C++ are checked as maps read from files are.
  auto map = std::make_shared<EnvironmentMap>();
  map->width = 3;
  map->height = 2;
  map->radiance.assign(6, Rgb(1.0));
  EnvironmentLight sky;
  sky.map = map;
  lecture.lights = { { "sky", sky } };
  EXPECT_EQ(
    errorOf(lecture, 0), "scene /lights/0/file: the map must be twice as wide as high, with width x height texels");
  map->width = 4;
  map->radiance.assign(8, Rgb(1.0));
  map->radiance[5].y = std::nan("");
  EXPECT_EQ(errorOf(lecture, 0), "scene /lights/0/file: every texel must be a finite non-negative radiance");
  map->radiance[5].y = 1;
  sky.estimator = EnvironmentEstimator::BruteForce;
  sky.bruteForceWidth = 3;
  lecture.lights = { { "sky", sky } };
  EXPECT_EQ(errorOf(lecture, 0),
    "scene /lights/0/brute_force_width: must be an even number that divides the map's "
    "width (4), or at least that width");
  sky.bruteForceWidth = 2;
  lecture.lights = { { "sky", sky } };
  EXPECT_EQ(errorOf(lecture, 0), "");
}

// The kernel evaluates SH irradiance as a polynomial in its vectorised loops; it must be the
// estimator's eq. 13, with the map turned.
TEST(DistributedLightsFilter, VectorisedShIrradianceIsTheEstimators)
{
  vtkSmartPointer<vtkPolyData> sphere = shadelab::testing::exactSphere(30);
  EnvironmentLight environment;
  environment.map = std::make_shared<const EnvironmentMap>(
    readEnvironmentMap(shadelab::testing::sourcePath("data/envmaps/studio_small_03_1k.hdr")));
  environment.rotationDegrees = 37;
  environment.color = { 1.0, 0.5, 0.25 };
  environment.intensity = 0.04;
  Scene scene = shinyScene();
  scene.lights = { { "sky", environment } };
  vtkSmartPointer<vtkPolyData> output = shadeWithFilter(sphere, scene, { "sky_irradiance" });
  vtkDataArray* irradiance = output->GetPointData()->GetArray("sky_irradiance");
  vtkDataArray* normals = sphere->GetPointData()->GetNormals();
  const EnvironmentLightEstimator estimator(environment, 0, LobeModel{});
  double largest = 0;
  for (vtkIdType i = 0; i < sphere->GetNumberOfPoints(); ++i)
  {
    SurfacePoint point;
    normals->GetTuple(i, &point.normal.x);
    const Rgb expected = estimator.estimate(point).irradiance;
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_NEAR(irradiance->GetComponent(i, c), expected[c], 1e-12 * std::max(1.0, std::abs(expected[c])));
      largest = std::max(largest, std::abs(expected[c]));
    }
  }
  EXPECT_GT(largest, 0.1);
}

// A vertex with a NaN coordinate gets 0 in every array, and one without a normal no light.
TEST(DistributedLightsFilter, NonFiniteAndNormalLessVerticesGetNothing)
{
  vtkSmartPointer<vtkPolyData> sphere = shadelab::testing::exactSphere(12);
  sphere->GetPoints()->SetPoint(5, std::nan(""), 0, 0);
  sphere->GetPointData()->GetNormals()->SetTuple3(7, 0, 0, 0);
  Scene scene = shinyScene();
  AreaLight bulb;
  bulb.shape = SphereEmitter{ { 0, 0, 3 }, 1 };
  bulb.estimator = AreaEstimator::MonteCarlo;
  EnvironmentLight sky;
  sky.map = singleTexelMap(3, 3, Rgb(5.0));
  scene.lights = { { "bulb", bulb }, { "sky", sky } };
  vtkSmartPointer<vtkPolyData> output = shadeWithFilter(sphere, scene, { "all" });
  vtkPointData* arrays = output->GetPointData();
  for (int a = 0; a < arrays->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* array = arrays->GetArray(a);
    if (std::string(array->GetName()) == "Normals" || std::string(array->GetName()) == "shading_flags")
    {
      continue;
    }
    for (const vtkIdType vertex : { 5, 7 })
    {
      for (int c = 0; c < array->GetNumberOfComponents(); ++c)
      {
        EXPECT_EQ(array->GetComponent(vertex, c), 0.0) << array->GetName() << " at vertex " << vertex;
      }
    }
  }
  EXPECT_EQ(arrays->GetArray("shading_flags")->GetComponent(5, 0), FlagNonFiniteInput);
  EXPECT_EQ(arrays->GetArray("shading_flags")->GetComponent(7, 0), FlagDegenerateNormal);
}
