#include "InterreflectionStudies.h"

#include "BenchmarkMeshes.h"
#include "vtkInterreflectionFilter.h"

#include "vtkDoubleArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkSphereSource.h"

#include <cmath>

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
}
