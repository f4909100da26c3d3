#include "InterreflectionStudies.h"

#include "BenchmarkMeshes.h"
#include "EnvironmentMap.h"
#include "NumberText.h"
#include "VtkErrorCapture.h"
#include "vtkInterreflectionFilter.h"
#include "vtkLocalReflectanceFilter.h"

#include "vtkDoubleArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkSphereSource.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

namespace shadelab::app
{
namespace
{
constexpr double rho = 0.8;
constexpr double pi = 3.14159265358979323846;

/// The unit sphere's cap within `halfAngle` of its pole, normals inward, covering the fraction
/// f = (1 - cos halfAngle) / 2 of the sphere; its direct radiosity under a sky of pi L = 1 is
/// rho (1 - f) everywhere (each point sees the cap with f of its cosine-weighted hemisphere).
vtkSmartPointer<vtkPolyData> bowl(double halfAngle, double f)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetRadius(1);
  sphere->SetThetaResolution(128);
  sphere->SetPhiResolution(64);
  sphere->SetEndPhi(halfAngle * 180 / pi);
  sphere->Update();
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->DeepCopy(sphere->GetOutput());
  vtkDataArray* normals = mesh->GetPointData()->GetNormals();
  vtkNew<vtkDoubleArray> radiosity;
  radiosity->SetName("diffuse");
  radiosity->SetNumberOfComponents(3);
  radiosity->SetNumberOfTuples(mesh->GetNumberOfPoints());
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    double p[3];
    mesh->GetPoint(i, p);
    normals->SetTuple3(i, -p[0], -p[1], -p[2]);
    radiosity->SetTuple3(i, rho * (1 - f), rho * (1 - f), rho * (1 - f));
  }
  mesh->GetPointData()->AddArray(radiosity);
  return mesh;
}

struct BowlRun
{
  Differences error; // of the indirect diffuse term kd E, against the closed form
  double restBound = 0;
  double milliseconds = 0;
};

/// The filter's indirect diffuse term after `bounces` bounces against the converged series'
/// closed form, rho E, E = (1 - f) sum_{n>=1} (rho f)^n = (1 - f) rho f / (1 - rho f), over the
/// bowl's vertices: what the bounces left out and the gather's noise together.
BowlRun gatherOnBowl(vtkPolyData* mesh, double f, int bounces, int rays, int maxRepeats)
{
  vtkNew<vtkInterreflectionFilter> filter;
  filter->SetInputData(mesh);
  filter->SetAlbedo(rho, rho, rho);
  filter->SetBounces(bounces);
  filter->SetSamples(rays);
  BowlRun run;
  run.milliseconds = medianMilliseconds(
    [&]
    {
      filter->Modified();
      filter->Update();
    },
    maxRepeats, maxRepeats);
  const double expected = (1 - f) * rho * f / (1 - rho * f);
  vtkDataArray* indirect = filter->GetOutput()->GetPointData()->GetArray("indirect_irradiance");
  DifferenceSum sum;
  for (vtkIdType i = 0; i < indirect->GetNumberOfTuples(); ++i)
  {
    sum.add(rho * std::abs(indirect->GetComponent(i, 1) - expected));
  }
  run.error = sum.result();
  run.restBound = filter->GetRestBound();
  return run;
}

/// The bowl under a constant sky of pi L = 1 without shadows, every point lit with E = 1, kd
/// 0.8 and no other term, with the interreflection given.
Scene skyOverBowl(const Interreflection& interreflection)
{
  auto sky = std::make_shared<EnvironmentMap>();
  sky->width = 64;
  sky->height = 32;
  sky->radiance.assign(std::size_t(sky->width * sky->height), Rgb(1 / pi));
  EnvironmentLight map;
  map.map = sky;
  map.file = "a constant sky";
  // Drawn by the cosine, a constant sky's every sample is pi L: E exact, with no standard error,
  // under any count, and under a tolerance the first round's.
  map.estimator = EnvironmentEstimator::MonteCarlo;
  map.directions = EnvironmentDirections::Cosine;
  map.sampling = { 16, true, interreflection.sampling.fromTolerance, 1024 };
  Scene scene;
  scene.material.ka = scene.material.ks = Rgb(0.0);
  scene.material.kd = Rgb(rho);
  scene.lights = { { "sky", map } };
  scene.interreflection = interreflection;
  return scene;
}

/// A run of the whole filter on the bowl: its median time, the error of its indirect diffuse
/// term at 95% of the vertices and at most, and under a tolerance the plan's choice.
struct PlannedRun
{
  double milliseconds = 0;
  double percentile95 = 0, largest = 0, rms = 0;
  InterreflectionChoice choice;
};

/// The bowl shaded under the scene (its normals as they are), against the closed form of the
/// indirect diffuse term without shadows: B_0 = kd everywhere, E_n = f (kd f)^(n-1) B_0, so
/// kd E = kd^2 f / (1 - kd f) after every bounce.
PlannedRun shadeBowl(vtkPolyData* mesh, double f, const Scene& scene, double tolerance, int maxRepeats)
{
  vtkNew<vtkPolyData> lit; // the bowl's geometry and normals, without the radiosity 14 gives it
  lit->ShallowCopy(mesh);
  lit->GetPointData()->RemoveArray("diffuse");
  vtkNew<vtkLocalReflectanceFilter> filter;
  filter->SetInputData(lit);
  filter->SetScene(scene);
  filter->SetArraySelection({ "indirect" });
  filter->SetOutputPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  filter->SetOrientNormalsOutward(false);
  filter->SetTolerance(tolerance);
  vtkNew<VtkErrorCapture> failure;
  failure->watch(filter);
  PlannedRun run;
  run.milliseconds = medianMilliseconds(
    [&]
    {
      filter->Modified();
      filter->Update();
    },
    maxRepeats, maxRepeats);
  vtkDataArray* indirect = filter->GetOutput()->GetPointData()->GetArray("indirect");
  if (!indirect)
  {
    throw std::runtime_error("study 14c: the bowl could not be shaded: " + failure->message());
  }
  const double expected = rho * rho * f / (1 - rho * f);
  std::vector<double> errors(static_cast<std::size_t>(indirect->GetNumberOfTuples()));
  DifferenceSum sum;
  for (vtkIdType i = 0; i < indirect->GetNumberOfTuples(); ++i)
  {
    errors[std::size_t(i)] = std::abs(indirect->GetComponent(i, 1) - expected);
    sum.add(errors[std::size_t(i)]);
  }
  run.rms = sum.result().rms;
  std::sort(errors.begin(), errors.end());
  run.percentile95 = errors[errors.size() * 95 / 100];
  run.largest = errors.back();
  if (tolerance > 0)
  {
    run.choice = *filter->GetMethodPlan()->interreflection;
  }
  return run;
}

/// The study's bowl: 3/4 of the unit sphere.
struct StudyBowl
{
  double halfAngle = 2 * pi / 3;
  double f = (1 - std::cos(halfAngle)) / 2;
  vtkSmartPointer<vtkPolyData> mesh = bowl(halfAngle, f);
  std::string note =
    "a bowl of 3/4 of the unit sphere under a sky of pi L = 1, kd 0.8; |kd E - the converged series' closed form|";
};
}

std::vector<AccuracyRow> interreflectionBouncesStudy(int maxRepeats, ChartSpec& chart)
{
  const StudyBowl bowl;
  std::vector<AccuracyRow> rows;
  ChartSeries largest{ "largest error (256 rays)", {}, {}, true, palette[0], true };
  ChartSeries rms{ "RMS error (256 rays)", {}, {}, true, palette[1], true };
  ChartSeries truncation{ "what the rest add: rho (1 - f) sum_{n>K} (rho f)^n", {}, {}, true, palette[7] };
  truncation.dashed = true;
  ChartSeries bound{ "the bound that auto stops on: max B_K rho / (1 - rho)", {}, {}, true, palette[3] };
  bound.dashed = true;
  for (int bounces = 1; bounces <= 10; ++bounces)
  {
    const BowlRun run = gatherOnBowl(bowl.mesh, bowl.f, bounces, 256, maxRepeats);
    rows.push_back({ "14 interreflection bounces", "K bounces (256 rays)", "bounces", double(bounces),
      bowl.mesh->GetNumberOfPoints(), run.milliseconds, run.error.largest, run.error.rms, run.restBound,
      bowl.note + "; predicted: the bound on the rest that auto stops on" });
    for (ChartSeries* series : { &largest, &rms, &truncation, &bound })
    {
      series->x.push_back(bounces);
    }
    largest.y.push_back(run.error.largest);
    rms.y.push_back(run.error.rms);
    truncation.y.push_back(rho * (1 - bowl.f) * std::pow(rho * bowl.f, bounces + 1) / (1 - rho * bowl.f));
    bound.y.push_back(run.restBound);
  }
  chart.series = { truncation, bound, largest, rms };
  chart.title = "interreflection in a bowl of 3/4 of a sphere, kd 0.8: error against the bounces";
  chart.xTitle = "bounces K";
  chart.yTitle = "|kd E_indirect - closed form|";
  chart.logY = true;
  chart.legendOutside = true;
  return rows;
}

std::vector<AccuracyRow> interreflectionRaysStudy(int maxRepeats, ChartSpec& chart)
{
  const StudyBowl bowl;
  std::vector<AccuracyRow> rows;
  ChartSeries largest{ "largest error (64 bounces)", {}, {}, true, palette[0], true };
  ChartSeries rms{ "RMS error (64 bounces)", {}, {}, true, palette[1], true };
  ChartSeries slope{ "1 / sqrt(N), through the first RMS", {}, {}, true, palette[7] };
  slope.dashed = true;
  for (const int rays : { 16, 64, 256, 1024 })
  {
    const BowlRun run = gatherOnBowl(bowl.mesh, bowl.f, 64, rays, maxRepeats);
    rows.push_back({ "14b interreflection rays", "gather rays (64 bounces)", "rays", double(rays),
      bowl.mesh->GetNumberOfPoints(), run.milliseconds, run.error.largest, run.error.rms, std::nullopt, bowl.note });
    for (ChartSeries* series : { &largest, &rms, &slope })
    {
      series->x.push_back(rays);
    }
    largest.y.push_back(run.error.largest);
    rms.y.push_back(run.error.rms);
    slope.y.push_back(rms.y.front() * std::sqrt(16.0 / rays));
  }
  chart.series = { slope, largest, rms };
  chart.title = "interreflection in a bowl of 3/4 of a sphere, kd 0.8: error against the gather's rays";
  chart.xTitle = "gather rays per vertex (stratified)";
  chart.yTitle = "|kd E_indirect - closed form|";
  chart.logX = true;
  chart.logY = true;
  return rows;
}

std::vector<AccuracyRow> interreflectionPlanStudy(int maxRepeats, ChartSpec& chart)
{
  const StudyBowl bowl;
  const std::string note = "the bowl of 14 under a constant sky of pi L = 1 without shadows, kd 0.8, through "
                           "vtkLocalReflectanceFilter; |indirect - kd^2 f / (1 - kd f)|";
  auto at95 = [](const PlannedRun& run) { return "; " + scientific(run.percentile95) + " at 95% of the vertices"; };
  std::vector<AccuracyRow> rows;
  std::vector<ChartSeries> fixed;
  int colour = 0;
  for (const int bounces : { 2, 4, 8, 16 })
  {
    ChartSeries series{ std::to_string(bounces) + " bounces, fixed: 16, 64, 256, 1024" +
        (bounces == 16 ? ", 4096" : "") + " rays",
      {}, {}, true, palette[colour++], true };
    for (const int rays : { 16, 64, 256, 1024, 4096 })
    {
      if (rays == 4096 && bounces != 16) // the plan's most, beside the bounces it needs
      {
        continue;
      }
      const PlannedRun run =
        shadeBowl(bowl.mesh, bowl.f, skyOverBowl({ bounces, { rays, true, false, rays }, false }), 0, maxRepeats);
      rows.push_back({ "14c interreflection time", std::to_string(bounces) + " bounces", "rays", double(rays),
        bowl.mesh->GetNumberOfPoints(), run.milliseconds, run.largest, run.rms, std::nullopt, note + at95(run) });
      series.x.push_back(run.milliseconds);
      series.y.push_back(run.percentile95);
    }
    fixed.push_back(series);
  }
  ChartSeries planned{ "the plan of a tolerance T = 0.1, 0.03, 0.01 (auto, at most 4096 rays)", {}, {}, false,
    palette[4] };
  ChartSeries asked{ "interreflection's share of each, T / 2", {}, {}, false, palette[7] };
  for (const double tolerance : { 0.1, 0.03, 0.01 })
  {
    Interreflection automatic;
    automatic.bouncesFromTolerance = true;
    automatic.sampling.fromTolerance = true;
    automatic.sampling.maximum = 4096;
    const PlannedRun run = shadeBowl(bowl.mesh, bowl.f, skyOverBowl(automatic), tolerance, maxRepeats);
    rows.push_back({ "14c interreflection time", "tolerance's plan", "tolerance", tolerance,
      bowl.mesh->GetNumberOfPoints(), run.milliseconds, run.largest, run.rms, tolerance / 2,
      note + at95(run) + "; chose " + std::to_string(run.choice.bounces) + " bounces and " +
        std::to_string(run.choice.samples) +
        " rays (\"max_samples\": 4096), its estimate of the gather's error at 95% " +
        scientific(run.choice.estimatedSamplingError.value_or(0)) + "; predicted: its share" });
    planned.x.push_back(run.milliseconds);
    planned.y.push_back(run.percentile95);
    asked.x.push_back(run.milliseconds);
    asked.y.push_back(tolerance / 2);
  }
  chart.series = fixed;
  chart.series.push_back(asked);
  chart.series.push_back(planned);
  chart.title = "interreflection in the bowl: time against the error, fixed settings and a tolerance's plan";
  chart.xTitle = "time per run (ms, 2 threads)";
  chart.yTitle = "|indirect - closed form| at 95% of the vertices";
  chart.logX = true;
  chart.logY = true;
  chart.legendOutside = true;
  return rows;
}
}
