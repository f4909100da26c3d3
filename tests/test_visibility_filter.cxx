// Shadows and ambient occlusion through the filters: vtkMeshVisibilityFilter's arrays, and
// vtkLocalReflectanceFilter multiplying each shadowed light's terms by its visibility and the
// ambient term by the occlusion, bit for bit the unshadowed terms where nothing is hidden.
#include "ArrayComparison.h"
#include "FilterRun.h"
#include "TestMeshes.h"
#include "VtkErrorCapture.h"

#include "EnvironmentMap.h"
#include "ShadingFlags.h"
#include "vtkMeshVisibilityFilter.h"
#include "vtkShadingNormalsFilter.h"

#include "vtkCellArray.h"
#include "vtkFloatArray.h"
#include "vtkPointData.h"
#include "vtkSMPTools.h"
#include "vtkUnsignedCharArray.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

namespace
{
using namespace shadelab;

/// A sphere of radius 0.5 at height 1 over the square [-2, 2]^2 at z = 0 (TestMeshes.h).
vtkSmartPointer<vtkPolyData> sphereOverPlane(int planeResolution = 60)
{
  return shadelab::testing::sphereOverSquare(planeResolution, 60, { 0, 0, 1 }, 0.5);
}

Scene pointLightAbove(bool shadows)
{
  Scene scene;
  scene.material.ka = Rgb(0.2);
  scene.viewer.position = glm::dvec3(0, -6, 4);
  PointLight bulb;
  bulb.position = { 0.3, 0.2, 3.0 };
  scene.lights = { { "ambient", AmbientLight{ Rgb(1.0), 1.0 } }, { "bulb", bulb, shadows } };
  return scene;
}

float valueOf(vtkPolyData* mesh, const char* name, vtkIdType i, int component = 0)
{
  vtkDataArray* array = mesh->GetPointData()->GetArray(name);
  return array ? static_cast<float>(array->GetComponent(i, component)) : NAN;
}

TEST(Shadows, ALightsTermsAreItsUnshadowedTermsTimesItsVisibility)
{
  vtkSmartPointer<vtkPolyData> mesh = sphereOverPlane();
  const std::vector<std::string> arrays = { "default", "bulb_diffuse", "bulb_specular", "bulb_cos_incidence" };
  vtkSmartPointer<vtkPolyData> lit = shadelab::testing::shadeWithFilter(mesh, pointLightAbove(false), arrays);
  vtkSmartPointer<vtkPolyData> shadowed = shadelab::testing::shadeWithFilter(mesh, pointLightAbove(true), arrays);
  ASSERT_NE(shadowed->GetPointData()->GetArray("bulb_visibility"), nullptr);
  EXPECT_EQ(lit->GetPointData()->GetArray("bulb_visibility"), nullptr);
  std::size_t hidden = 0;
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    const float v = valueOf(shadowed, "bulb_visibility", i);
    ASSERT_TRUE(v == 0.0f || v == 1.0f);
    hidden += v == 0.0f && valueOf(lit, "bulb_cos_incidence", i) > 0 ? 1 : 0;
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_EQ(valueOf(shadowed, "bulb_diffuse", i, c), v * valueOf(lit, "bulb_diffuse", i, c));
      EXPECT_EQ(valueOf(shadowed, "bulb_specular", i, c), v * valueOf(lit, "bulb_specular", i, c));
      EXPECT_EQ(valueOf(shadowed, "ambient", i, c), valueOf(lit, "ambient", i, c)); // no occlusion asked for
    }
    // Terms that do not depend on visibility are unchanged.
    EXPECT_EQ(valueOf(shadowed, "bulb_cos_incidence", i), valueOf(lit, "bulb_cos_incidence", i));
  }
  EXPECT_GT(hidden, 100u); // the sphere's shadow on the plane, facing the light
}

TEST(AmbientOcclusion, ScalesTheAmbientTermAndComesWithItsArrays)
{
  vtkSmartPointer<vtkPolyData> mesh = sphereOverPlane();
  Scene scene = pointLightAbove(false);
  scene.ambientOcclusion = AmbientOcclusion{};
  vtkSmartPointer<vtkPolyData> shaded = shadelab::testing::shadeWithFilter(mesh, scene, { "all" });
  for (const char* name : { "ambient_occlusion", "ambient_occlusion_std_error", "bent_normal", "sky_view_factor" })
  {
    ASSERT_NE(shaded->GetPointData()->GetArray(name), nullptr) << name;
  }
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); i += 7)
  {
    const float ao = valueOf(shaded, "ambient_occlusion", i);
    ASSERT_GE(ao, 0.0f);
    ASSERT_LE(ao, 1.0f);
    EXPECT_EQ(valueOf(shaded, "ambient", i), static_cast<float>(0.2 * double(ao)));
  }
  // The plane under the sphere's centre sees less sky: 1 - r^2 h / d^3 = 0.75 there.
  vtkIdType centre = 0;
  double nearest = INFINITY;
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    double p[3];
    mesh->GetPoint(i, p);
    if (p[2] == 0 && std::hypot(p[0], p[1]) < nearest)
    {
      nearest = std::hypot(p[0], p[1]);
      centre = i;
    }
  }
  EXPECT_NEAR(valueOf(shaded, "ambient_occlusion", centre), 0.75f,
    4 * valueOf(shaded, "ambient_occlusion_std_error", centre) + 0.02f); // and the tessellation
}

TEST(Visibility, OneAndTwoThreadsGiveTheSameBits)
{
  vtkSmartPointer<vtkPolyData> mesh = sphereOverPlane();
  Scene scene = pointLightAbove(true);
  scene.ambientOcclusion = AmbientOcclusion{};
  vtkSmartPointer<vtkPolyData> one, two;
  vtkSMPTools::LocalScope(
    vtkSMPTools::Config{ 1 }, [&] { one = shadelab::testing::shadeWithFilter(mesh, scene, { "all" }); });
  vtkSMPTools::LocalScope(
    vtkSMPTools::Config{ 2 }, [&] { two = shadelab::testing::shadeWithFilter(mesh, scene, { "all" }); });
  shadelab::testing::expectSamePointArrays(one, two);
}

TEST(AmbientOcclusion, ATolerancesShareSetsEachVertexsRaysTheSameOnAnyThreadCount)
{
  // "rays": "auto" under a tolerance: the plan's share of it is each vertex's target, which
  // its standard error meets unless it drew the maximum, and where each vertex stops does not
  // depend on the threads.
  vtkSmartPointer<vtkPolyData> mesh = sphereOverPlane();
  Scene scene = pointLightAbove(false);
  scene.lights[1].source = DistantLight{};
  scene.ambientOcclusion = AmbientOcclusion{};
  scene.ambientOcclusion->sampling.fromTolerance = true;
  scene.ambientOcclusion->sampling.maximum = 512;
  const auto one = shadelab::testing::shadeToTolerance(mesh, scene, 0.03, 1).output;
  const shadelab::testing::ToleranceRun two = shadelab::testing::shadeToTolerance(mesh, scene, 0.03, 2);
  const SamplingTarget target = *two.plan.occlusion->target;
  shadelab::testing::expectSamePointArrays(one, two.output);
  EXPECT_EQ(target.maximum, 512);
  EXPECT_NEAR(target.error, 0.03, 0.003) << "all but the arithmetic's part";
  vtkIdType atMaximum = 0;
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    const float rays = valueOf(one, "ambient_occlusion_rays", i);
    ASSERT_GE(rays, target.minimum);
    ASSERT_LE(rays, target.maximum);
    if (rays < target.maximum)
    {
      // The estimate stopped when its standard error was at most the target's; rounding both
      // to float keeps the order.
      ASSERT_LE(valueOf(one, "ambient_occlusion_std_error", i), static_cast<float>(target.standardError())) << i;
    }
    // Flagged exactly where it stopped at the maximum above its target.
    const bool above = valueOf(one, "ambient_occlusion_std_error", i) > static_cast<float>(target.standardError());
    ASSERT_EQ(valueOf(one, "ambient_occlusion_short_of_target", i), rays == target.maximum && above ? 1.0f : 0.0f) << i;
    atMaximum += rays == target.maximum ? 1 : 0;
  }
  EXPECT_LT(atMaximum, mesh->GetNumberOfPoints() / 10);
}

/// The sphere-over-plane scene's light as a disk of radius 0.6 at the bulb's place, facing down,
/// its shadows cast or not.
Scene diskLightAbove(bool shadows, AreaEstimator estimator)
{
  Scene scene = pointLightAbove(false);
  AreaLight panel;
  panel.shape = DiskEmitter{ { 0.3, 0.2, 3.0 }, { 0, 0, -1 }, 0.6 };
  panel.intensity = 2;
  panel.estimator = estimator;
  scene.lights[1] = { "panel", panel, shadows };
  return scene;
}

TEST(SoftShadows, AnAreaLightsTermsComeFromThePartOfItThatEachVertexSees)
{
  vtkSmartPointer<vtkPolyData> mesh = sphereOverPlane();
  const std::vector<std::string> arrays = { "default", "panel_irradiance", "panel_diffuse" };
  for (AreaEstimator estimator : { AreaEstimator::Exact, AreaEstimator::MonteCarlo })
  {
    vtkSmartPointer<vtkPolyData> lit =
      shadelab::testing::shadeWithFilter(mesh, diskLightAbove(false, estimator), arrays);
    vtkSmartPointer<vtkPolyData> shadowed =
      shadelab::testing::shadeWithFilter(mesh, diskLightAbove(true, estimator), arrays);
    ASSERT_NE(shadowed->GetPointData()->GetArray("panel_visibility_std_error"), nullptr);
    EXPECT_EQ(shadowed->GetPointData()->GetArray("panel_hidden_samples"), nullptr); // the rays' bits stay inside
    // In float64, as the filter computed them.
    auto value = [](vtkPolyData* shaded, const char* name, vtkIdType i, int c)
    { return shaded->GetPointData()->GetArray(name)->GetComponent(i, c); };
    std::size_t penumbra = 0, umbra = 0;
    for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
    {
      const double v = value(shadowed, "panel_visibility", i, 0);
      ASSERT_GE(v, 0.0);
      ASSERT_LE(v, 1.0);
      penumbra += v > 0 && v < 1 ? 1 : 0;
      umbra += v == 0 && value(lit, "panel_irradiance", i, 0) > 0 ? 1 : 0;
      for (int c = 0; c < 3; ++c)
      {
        const double seen = value(shadowed, "panel_irradiance", i, c), open = value(lit, "panel_irradiance", i, c);
        // Where every ray gets through, the unshadowed value bit for bit; the exact estimator's
        // E is the unshadowed one times the visible fraction; the diffuse term is kd E.
        if (v == 1)
        {
          EXPECT_EQ(seen, open) << i;
        }
        if (estimator == AreaEstimator::Exact)
        {
          EXPECT_EQ(seen, open * v) << i;
        }
        EXPECT_LE(seen, open * (1 + 1e-12) + 1e-15) << i;
        EXPECT_EQ(value(shadowed, "panel_diffuse", i, c), 0.8 * seen) << i;
      }
    }
    EXPECT_GT(penumbra, 100u); // the disk is wider than the sphere's shadow is sharp
    EXPECT_GT(umbra, 10u);     // under the sphere's centre the whole disk is hidden
  }
}

TEST(SoftShadows, OneAndTwoThreadsGiveTheSameBits)
{
  vtkSmartPointer<vtkPolyData> mesh = sphereOverPlane();
  const Scene scene = diskLightAbove(true, AreaEstimator::Exact);
  vtkSmartPointer<vtkPolyData> one, two;
  vtkSMPTools::LocalScope(
    vtkSMPTools::Config{ 1 }, [&] { one = shadelab::testing::shadeWithFilter(mesh, scene, { "all" }); });
  vtkSMPTools::LocalScope(
    vtkSMPTools::Config{ 2 }, [&] { two = shadelab::testing::shadeWithFilter(mesh, scene, { "all" }); });
  shadelab::testing::expectSamePointArrays(one, two);
}

TEST(SoftShadows, ATolerancesShareDrawsEachVertexsShadowRaysUntilItsEstimateMeetsIt)
{
  // The disk's samples "auto" under a tolerance: the visibility step draws each vertex's rays in
  // rounds until E and S meet the plan's targets (the exact estimator's E through its visible
  // fraction), the same bits on one and two threads; 95% of the vertices' E within its target
  // of 4096 fixed samples' E, and every vertex not at the maximum within its standard error.
  vtkSmartPointer<vtkPolyData> mesh = sphereOverPlane();
  for (AreaEstimator estimator : { AreaEstimator::Exact, AreaEstimator::MonteCarlo })
  {
    Scene scene = diskLightAbove(true, estimator);
    Scene fixed = scene;
    std::get<AreaLight>(scene.lights[1].source).sampling.fromTolerance = true;
    std::get<AreaLight>(fixed.lights[1].source).sampling.samples = 4096;
    const shadelab::testing::ToleranceRun one = shadelab::testing::shadeToTolerance(mesh, scene, 0.05, 1);
    const shadelab::testing::ToleranceRun two = shadelab::testing::shadeToTolerance(mesh, scene, 0.05, 2);
    shadelab::testing::expectSamePointArrays(one.output, two.output);
    EXPECT_TRUE(one.samplingReport.empty()) << one.samplingReport[0];
    EXPECT_EQ(one.output->GetPointData()->GetArray("panel_shadowed_terms"), nullptr); // the estimates stay inside
    const SamplingTarget target = *one.plan.lights[1].method.targets.irradiance;
    EXPECT_NEAR(target.error, 0.025, 1e-4) << "half of all but the arithmetic's few millionths; kd below 1";
    const vtkSmartPointer<vtkPolyData> reference = shadelab::testing::shadeWithFilter(mesh, fixed, { "all" });
    vtkIdType within = 0, penumbra = 0;
    for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
    {
      const double v = valueOf(one.output, "panel_visibility", i);
      penumbra += v > 0 && v < 1 ? 1 : 0;
      bool near = true;
      for (int c = 0; c < 3; ++c)
      {
        ASSERT_LE(valueOf(one.output, "panel_irradiance_std_error", i, c), static_cast<float>(target.standardError()))
          << i;
        near = near &&
          std::abs(valueOf(one.output, "panel_irradiance", i, c) - valueOf(reference, "panel_irradiance", i, c)) <=
            target.error;
      }
      within += near ? 1 : 0;
    }
    EXPECT_GT(penumbra, 100);
    EXPECT_GE(double(within), 0.95 * double(mesh->GetNumberOfPoints()))
      << within << " of " << mesh->GetNumberOfPoints();
    EXPECT_NE(one.output->GetFieldData()->GetAbstractArray("shadelab_visibility"), nullptr);
  }
}

TEST(SoftShadows, TheErrorAfterSamplingIsPredictedFromEachVertexsStandardErrors)
{
  // A shadowed disk and the ambient occlusion, both drawn to a tolerance. After the run the plan
  // estimates what 95% of the vertices err by, from each vertex's standard errors as the arrays hold
  // them: max over channels of max(1, kd) s_E + (ks s_S, the specular_std_error array) plus
  // max(1, ka La) s_AO (ka La = 0.2 here, so s_AO itself), whose quantile is recomputed here.
  vtkSmartPointer<vtkPolyData> mesh = sphereOverPlane();
  Scene scene = diskLightAbove(true, AreaEstimator::MonteCarlo);
  scene.material.kd = Rgb(1.5, 0.5, 0.25); // E's own array outweighs the red diffuse term
  std::get<AreaLight>(scene.lights[1].source).sampling.fromTolerance = true;
  scene.ambientOcclusion = AmbientOcclusion{};
  scene.ambientOcclusion->sampling.fromTolerance = true;
  const shadelab::testing::ToleranceRun run = shadelab::testing::shadeToTolerance(mesh, scene, 0.1, 2);
  std::vector<double> standardErrors;
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    double largest = 0;
    for (int c = 0; c < 3; ++c)
    {
      largest = std::max(largest,
        std::max(1.0, scene.material.kd[c]) * valueOf(run.output, "panel_irradiance_std_error", i, c) +
          valueOf(run.output, "panel_specular_std_error", i, c));
    }
    standardErrors.push_back(largest + valueOf(run.output, "ambient_occlusion_std_error", i));
  }
  const MethodPlan& plan = run.plan;
  ASSERT_TRUE(plan.estimatedSamplingError.has_value());
  const double reached = estimatedErrorQuantile(standardErrors, 0.95);
  EXPECT_NEAR(*plan.estimatedSamplingError, reached, 1e-6 * reached) << "the arrays hold float32";
  EXPECT_GT(reached, 0.0);
  EXPECT_LT(reached, plan.samplingError / 2) << "most vertices stop well under their share";
  EXPECT_DOUBLE_EQ(plan.estimatedError(), plan.predictedError() - plan.samplingError + *plan.estimatedSamplingError);
  EXPECT_EQ(plan.describe().back(),
    "after sampling: an error of about " + scientific(plan.estimatedError()) + " at 95% of the vertices (" +
      scientific(*plan.estimatedSamplingError) +
      " estimated from their standard errors, where the plan bounds sampling's part by " +
      scientific(plan.samplingError) + ")");
  EXPECT_NEAR(plan.samplingError, plan.predictedError() - plan.arithmeticError, 1e-12) << "no approximations here";
}

TEST(AmbientOcclusion, TheEstimateAfterSamplingOfALargeMeshIsThatOfEveryKthVertex)
{
  // 94,322 points: the estimate is taken over every other one by id, and is the quantile of all
  // of them (recomputed here from the array) to within a few parts in a thousand.
  vtkSmartPointer<vtkPolyData> mesh = sphereOverPlane(300);
  ASSERT_GT(mesh->GetNumberOfPoints(), 65536);
  Scene scene = pointLightAbove(false);
  scene.ambientOcclusion = AmbientOcclusion{};
  scene.ambientOcclusion->sampling.fromTolerance = true;
  const shadelab::testing::ToleranceRun run = shadelab::testing::shadeToTolerance(mesh, scene, 0.1, 2);
  std::vector<double> standardErrors;
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    standardErrors.push_back(valueOf(run.output, "ambient_occlusion_std_error", i)); // ka La 0.2: weight 1
  }
  const double whole = estimatedErrorQuantile(standardErrors, targetConfidence);
  ASSERT_TRUE(run.plan.estimatedSamplingError.has_value());
  EXPECT_GT(whole, 0.0);
  EXPECT_NEAR(*run.plan.estimatedSamplingError, whole, 0.005 * whole);
}

/// The sphere over the plane under a constant sky of radiance 1, with or without its shadows.
Scene constantSky(bool shadows, EnvironmentEstimator estimator, EnvironmentDirections directions)
{
  Scene scene = pointLightAbove(false);
  auto map = std::make_shared<EnvironmentMap>();
  map->width = 64;
  map->height = 32;
  map->radiance.assign(64 * 32, Rgb(1.0));
  EnvironmentLight sky;
  sky.map = map;
  sky.file = "constant";
  sky.estimator = estimator;
  sky.directions = directions;
  scene.lights[1] = { "sky", sky, shadows };
  return scene;
}

TEST(SoftShadows, AMapsTermsComeFromTheSkyEachVertexSees)
{
  vtkSmartPointer<vtkPolyData> mesh = sphereOverPlane();
  const std::vector<std::string> arrays = { "default", "sky_irradiance", "sky_diffuse" };
  for (EnvironmentEstimator estimator : { EnvironmentEstimator::MonteCarlo, EnvironmentEstimator::BruteForce })
  {
    const Scene open = constantSky(false, estimator, EnvironmentDirections::Mis);
    const Scene shadowedScene = constantSky(true, estimator, EnvironmentDirections::Mis);
    vtkSmartPointer<vtkPolyData> lit = shadelab::testing::shadeWithFilter(mesh, open, arrays);
    vtkSmartPointer<vtkPolyData> shadowed = shadelab::testing::shadeWithFilter(
      mesh, shadowedScene, { "default", "sky_irradiance", "sky_diffuse", "sky_specular_std_error" });
    ASSERT_NE(shadowed->GetPointData()->GetArray("sky_visibility_std_error"), nullptr);
    ASSERT_NE(shadowed->GetPointData()->GetArray("sky_specular_std_error"), nullptr); // sampled, even by the sum
    EXPECT_EQ(shadowed->GetPointData()->GetArray("sky_hidden_samples"), nullptr);
    auto value = [](vtkPolyData* shaded, const char* name, vtkIdType i, int c)
    { return shaded->GetPointData()->GetArray(name)->GetComponent(i, c); };
    std::size_t whole = 0, shaded = 0;
    for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
    {
      const double v = value(shadowed, "sky_visibility", i, 0);
      ASSERT_GE(v, 0.0);
      ASSERT_LE(v, 1.0);
      whole += v == 1 ? 1 : 0;
      shaded += v < 0.9 ? 1 : 0;
      const double seen = value(shadowed, "sky_irradiance", i, 0), unshadowed = value(lit, "sky_irradiance", i, 0);
      if (v == 1)
      {
        EXPECT_EQ(seen, unshadowed) << i; // the top of the sphere, and the plane's far corners
      }
      if (estimator == EnvironmentEstimator::BruteForce)
      {
        EXPECT_EQ(seen, unshadowed * v) << i;
      }
      EXPECT_EQ(value(shadowed, "sky_diffuse", i, 0), 0.8 * seen) << i;
    }
    EXPECT_GT(whole, 100u);
    EXPECT_GT(shaded, 100u); // the plane under the sphere, and the sphere's underside
  }
}

TEST(SoftShadows, AMapsShadowsAreTheSameBitsOnOneAndTwoThreads)
{
  vtkSmartPointer<vtkPolyData> mesh = sphereOverPlane();
  const Scene scene = constantSky(true, EnvironmentEstimator::SphericalHarmonics, EnvironmentDirections::Mis);
  vtkSmartPointer<vtkPolyData> one, two;
  vtkSMPTools::LocalScope(
    vtkSMPTools::Config{ 1 }, [&] { one = shadelab::testing::shadeWithFilter(mesh, scene, { "all" }); });
  vtkSMPTools::LocalScope(
    vtkSMPTools::Config{ 2 }, [&] { two = shadelab::testing::shadeWithFilter(mesh, scene, { "all" }); });
  shadelab::testing::expectSamePointArrays(one, two);
}

/// Shades the sphere over the plane with the light, with shadows, and counts the vertices with
/// FlagLightEnclosed and those of the plane with any of the light's irradiance or diffuse term.
struct EnclosureRun
{
  std::size_t flagged = 0, litPlanePoints = 0;
  std::string report;
};

EnclosureRun shadeWithLightAt(const LightSource& light)
{
  vtkSmartPointer<vtkPolyData> mesh = sphereOverPlane();
  Scene scene = pointLightAbove(false);
  scene.lights[1] = { "inner", light, true };
  vtkNew<vtkLocalReflectanceFilter> filter;
  filter->SetInputData(mesh);
  filter->SetScene(scene);
  filter->SetArraySelection({ "default", "inner_diffuse" });
  filter->Update();
  EnclosureRun run;
  run.report = filter->GetVisibilityReport();
  vtkPolyData* shaded = filter->GetOutput();
  for (vtkIdType i = 0; i < shaded->GetNumberOfPoints(); ++i)
  {
    run.flagged += (int(valueOf(shaded, "shading_flags", i)) & FlagLightEnclosed) ? 1 : 0;
    const bool onPlane = shaded->GetPoint(i)[2] == 0;
    run.litPlanePoints += onPlane && valueOf(shaded, "inner_diffuse", i) > 0 ? 1 : 0;
  }
  return run;
}

TEST(VisibilityFailurePoints, ALightInsideAClosedMeshIsDarkAndFlagged)
{
  // The sphere (radius 0.5 at height 1) is closed: a bulb or a small sphere light at its
  // centre lights nothing outside, and every vertex it is hidden from has flag 128.
  PointLight bulb;
  bulb.position = { 0, 0, 1 };
  AreaLight ball;
  ball.shape = SphereEmitter{ { 0, 0, 1 }, 0.1 };
  ball.estimator = AreaEstimator::MonteCarlo;
  const std::size_t points = sphereOverPlane()->GetNumberOfPoints();
  for (const LightSource& light : { LightSource(bulb), LightSource(ball) })
  {
    const EnclosureRun inside = shadeWithLightAt(light);
    EXPECT_EQ(inside.litPlanePoints, 0u);
    // The bulb is hidden from every vertex (the sphere's own from behind); the ball from the
    // vertices that face it, the plane's and none of the sphere's.
    EXPECT_GT(inside.flagged, std::holds_alternative<PointLight>(light) ? points - 1 : points / 2);
    EXPECT_NE(inside.report.find("The light 'inner' is inside the mesh (every ray from it meets a triangle): no "
                                 "vertex outside gets its light (shading_flags 128)."),
      std::string::npos)
      << inside.report;
  }
  // Above the sphere the same lights are not enclosed: no flag, and the plane is lit.
  bulb.position = { 0, 0, 2 };
  ball.shape = SphereEmitter{ { 0, 0, 2 }, 0.1 };
  for (const LightSource& light : { LightSource(bulb), LightSource(ball) })
  {
    const EnclosureRun outside = shadeWithLightAt(light);
    EXPECT_EQ(outside.flagged, 0u);
    EXPECT_GT(outside.litPlanePoints, 100u);
    EXPECT_EQ(outside.report.find("inside the mesh"), std::string::npos);
  }
}

TEST(Visibility, TheBvhIsBuiltOnceWhileTheMeshIsUnchanged)
{
  vtkSmartPointer<vtkPolyData> mesh = sphereOverPlane();
  vtkNew<vtkLocalReflectanceFilter> filter;
  filter->SetInputData(mesh);
  filter->SetScene(pointLightAbove(true));
  filter->Update();
  EXPECT_NE(filter->GetVisibilityReport().find("BVH built in "), std::string::npos) << filter->GetVisibilityReport();
  const std::vector<float> first(
    static_cast<float*>(filter->GetOutput()->GetPointData()->GetArray("bulb_visibility")->GetVoidPointer(0)),
    static_cast<float*>(filter->GetOutput()->GetPointData()->GetArray("bulb_visibility")->GetVoidPointer(0)) +
      mesh->GetNumberOfPoints());
  // Another material: the same mesh, the same BVH, the same visibility.
  Scene shinier = pointLightAbove(true);
  shinier.material.shininess = 80;
  filter->SetScene(shinier);
  filter->Update();
  EXPECT_NE(filter->GetVisibilityReport().find("BVH reused"), std::string::npos) << filter->GetVisibilityReport();
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    ASSERT_EQ(valueOf(filter->GetOutput(), "bulb_visibility", i), first[static_cast<std::size_t>(i)]);
  }
  // The mesh moved: a new BVH, and the shadow moves with it.
  double p[3];
  mesh->GetPoints()->GetPoint(0, p);
  mesh->GetPoints()->SetPoint(0, p[0], p[1], p[2] + 0.01);
  mesh->GetPoints()->Modified();
  filter->Update();
  EXPECT_NE(filter->GetVisibilityReport().find("BVH built in "), std::string::npos) << filter->GetVisibilityReport();
}

/// vtkMeshVisibilityFilter's output for the mesh with these point normals.
vtkSmartPointer<vtkPolyData> seen(vtkPolyData* mesh, const Scene& scene)
{
  vtkNew<vtkShadingNormalsFilter> normals;
  normals->SetInputData(mesh);
  normals->OrientOutwardOff();
  vtkNew<vtkMeshVisibilityFilter> visibility;
  visibility->SetInputConnection(normals->GetOutputPort());
  visibility->SetScene(scene);
  visibility->Update();
  auto output = vtkSmartPointer<vtkPolyData>::New();
  output->ShallowCopy(visibility->GetOutput());
  return output;
}

TEST(Visibility, APointAtInfinityCastsNoRaysAndHidesNothingElse)
{
  vtkSmartPointer<vtkPolyData> mesh = sphereOverPlane();
  const vtkSmartPointer<vtkPolyData> before = seen(mesh, pointLightAbove(true));
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->DeepCopy(mesh->GetPoints());
  points->SetPoint(0, INFINITY, 0, 0); // a corner of the plane
  auto broken = vtkSmartPointer<vtkPolyData>::New();
  broken->ShallowCopy(mesh);
  broken->SetPoints(points);
  const vtkSmartPointer<vtkPolyData> after = seen(broken, pointLightAbove(true));
  ASSERT_NE(after->GetPointData()->GetArray("bulb_visibility"), nullptr);
  EXPECT_EQ(valueOf(after, "bulb_visibility", 0), 0.0f);
  std::size_t differing = 0, hidden = 0;
  for (vtkIdType i = 1; i < mesh->GetNumberOfPoints(); ++i)
  {
    differing += valueOf(after, "bulb_visibility", i) != valueOf(before, "bulb_visibility", i) ? 1 : 0;
    hidden += valueOf(after, "bulb_visibility", i) == 0.0f ? 1 : 0;
  }
  // Only the rays that passed through the corner's two triangles can change.
  EXPECT_LE(differing, 2u);
  EXPECT_GT(hidden, 100u);
}

TEST(AmbientOcclusion, TwoSidedShadingTakesTheSideTheViewerSees)
{
  // The plane under the sphere seen from below with a two-sided material: the kernel shades
  // its underside, which sees the open sky below, so its occlusion is 1 everywhere; seen
  // from above it is the sphere's form factor.
  vtkSmartPointer<vtkPolyData> mesh = sphereOverPlane();
  Scene scene = pointLightAbove(false);
  scene.ambientOcclusion = AmbientOcclusion{};
  scene.material.twoSided = true;
  scene.viewer.position = glm::dvec3(0, 0, -6);
  const vtkSmartPointer<vtkPolyData> below = seen(mesh, scene);
  scene.viewer.position = glm::dvec3(0, 0, 6);
  const vtkSmartPointer<vtkPolyData> above = seen(mesh, scene);
  double smallestBelow = 1, smallestAbove = 1;
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    double p[3];
    mesh->GetPoint(i, p);
    if (p[2] == 0)
    {
      smallestBelow = std::min<double>(smallestBelow, valueOf(below, "ambient_occlusion", i));
      smallestAbove = std::min<double>(smallestAbove, valueOf(above, "ambient_occlusion", i));
    }
  }
  EXPECT_EQ(smallestBelow, 1.0);
  EXPECT_LT(smallestAbove, 0.8);
}

using shadelab::testing::filterError;

TEST(Visibility, WhatIsRefusedAndWhy)
{
  vtkSmartPointer<vtkPolyData> mesh = sphereOverPlane();
  // (The bulb is within the mesh's bounding sphere, where no bound holds: a sun instead.)
  Scene sunAbove = pointLightAbove(true);
  sunAbove.lights[1].source = DistantLight{};
  EXPECT_EQ(filterError(mesh, sunAbove, 1e-3), "") << "hard shadows are exact: a tolerance covers them";
  Scene occluded = sunAbove;
  occluded.lights[1].shadows = false;
  occluded.ambientOcclusion = AmbientOcclusion{};
  occluded.ambientOcclusion->sampling.fromTolerance = true;
  const std::string untargeted = "scene /ambient_occlusion/rays: \"auto\" takes its count of rays from a tolerance: "
                                 "give one (shadelab shade --tolerance, the filter's Tolerance), or a number of rays";
  EXPECT_EQ(filterError(mesh, occluded), untargeted);
  EXPECT_EQ(filterError(mesh, occluded, 0.05), "");
  {
    // The visibility filter alone, which has no tolerance, on the mesh with its normals.
    vtkNew<vtkShadingNormalsFilter> normals;
    normals->SetInputData(mesh);
    auto aloneError = [&](const Scene& scene)
    {
      vtkNew<vtkMeshVisibilityFilter> alone;
      vtkNew<app::VtkErrorCapture> errors;
      errors->watch(alone);
      alone->SetInputConnection(normals->GetOutputPort());
      alone->SetScene(scene);
      alone->Update();
      return errors->message();
    };
    EXPECT_EQ(aloneError(occluded), untargeted);
    Scene softAuto = diskLightAbove(true, AreaEstimator::Exact);
    std::get<AreaLight>(softAuto.lights[1].source).sampling.fromTolerance = true;
    EXPECT_EQ(aloneError(softAuto),
      "scene /lights/1/samples: \"auto\" with shadows takes the count of light 'panel' "
      "from a tolerance's plan: shade it with vtkLocalReflectanceFilter under a tolerance "
      "(shadelab shade --tolerance), or give it a number of samples");
  }
  Scene shadowedAmbient = pointLightAbove(false);
  shadowedAmbient.lights.push_back({ "sky", AmbientLight{}, true });
  EXPECT_EQ(filterError(mesh, shadowedAmbient),
    "scene /lights/2/shadows: only distant, headlight, point, spot, polygon, rectangle, disk, sphere and "
    "environment lights cast shadows (an ambient light has no direction; the mesh's shadowing of it is ambient "
    "occlusion): remove \"shadows\" from this light");

  vtkNew<vtkMeshVisibilityFilter> alone;
  vtkNew<app::VtkErrorCapture> errors;
  errors->watch(alone);
  alone->SetInputData(mesh); // no point normals
  alone->SetScene(pointLightAbove(true));
  alone->Update();
  EXPECT_EQ(errors->message(),
    "the mesh needs one 3-component point normal per point to cast rays from: run "
    "vtkShadingNormalsFilter first (vtkLocalReflectanceFilter does)");

  // A cell with a point id past the points, alone (the filter checks its cells by default).
  vtkNew<vtkShadingNormalsFilter> normals;
  normals->SetInputData(mesh);
  normals->Update();
  vtkNew<vtkPolyData> broken;
  broken->DeepCopy(normals->GetOutput());
  const vtkIdType pastTheEnd[3] = { 0, 1, broken->GetNumberOfPoints() + 4 };
  broken->GetPolys()->InsertNextCell(3, pastTheEnd);
  vtkNew<vtkMeshVisibilityFilter> checking;
  vtkNew<app::VtkErrorCapture> cellErrors;
  cellErrors->watch(checking);
  checking->SetInputData(broken);
  checking->SetScene(pointLightAbove(true));
  checking->Update();
  EXPECT_EQ(cellErrors->message(), "the mesh's cells use point id 7207, but it has 7203 points: the mesh is corrupt");
  ASSERT_EQ(broken->GetNumberOfPoints(), 7203);
}
}
