#include "RayBenchmark.h"

#include "BenchmarkMeshes.h"
#include "Chart.h"
#include "CsvText.h"
#include "MeshFiles.h"

#include "AreaLightEstimator.h"
#include "EnvironmentLightEstimator.h"
#include "EnvironmentMap.h"
#include "OccluderMesh.h"
#include "PolygonIrradiance.h"
#include "SampleSequence.h"
#include "SampleWarps.h"
#include "Visibility.h"
#include "vtkShadingNormalsFilter.h"

#include "vtkCellArray.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkSMPTools.h"
#include "vtkStaticCellLocator.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <numeric>
#include <sstream>

namespace shadelab::app
{
namespace
{
namespace fs = std::filesystem;

/// A mesh as the rays see it: its vertices (unit normals) and its occluders.
struct RayMesh
{
  std::string name;
  vtkSmartPointer<vtkPolyData> data;
  std::vector<RayVertex> vertices;
  std::unique_ptr<OccluderMesh> occluders;
  double buildMilliseconds = 0;
  double radius = 1;
  glm::dvec3 centre{ 0.0 };
};

RayMesh rayMesh(const std::string& name, vtkPolyData* mesh, int repeats)
{
  vtkNew<vtkShadingNormalsFilter> normals;
  normals->SetInputData(mesh);
  normals->Update();
  RayMesh prepared{ name, normals->GetOutput(), {}, nullptr };
  vtkPolyData* data = prepared.data;
  vtkDataArray* n = data->GetPointData()->GetNormals();
  double bounds[6];
  data->GetBounds(bounds);
  prepared.centre = { 0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]), 0.5 * (bounds[4] + bounds[5]) };
  prepared.radius = 0.5 * data->GetLength();
  for (vtkIdType i = 0; i < data->GetNumberOfPoints(); ++i)
  {
    double p[3], normal[3];
    data->GetPoint(i, p);
    n->GetTuple(i, normal);
    const glm::dvec3 unit(normal[0], normal[1], normal[2]);
    prepared.vertices.push_back({ { p[0], p[1], p[2] }, glm::length(unit) > 0 ? glm::normalize(unit) : unit, i });
  }
  // The polygons as the core reads them: VTK 9 keeps 64-bit offsets and ids for these meshes.
  vtkCellArray* polys = data->GetPolys();
  const PolygonList list{ polys->GetOffsetsArray64()->GetPointer(0), polys->GetConnectivityArray64()->GetPointer(0),
    static_cast<std::size_t>(polys->GetNumberOfCells()) };
  auto* xyz = vtkFloatArray::SafeDownCast(data->GetPoints()->GetData());
  if (!xyz)
  {
    throw UserError(name + ": the benchmark expects float points");
  }
  prepared.buildMilliseconds = medianMilliseconds(
    [&]
    {
      prepared.occluders =
        std::make_unique<OccluderMesh>(PackedPoints<float>{ xyz->GetPointer(0) }, prepared.vertices.size(), list);
    },
    repeats, repeats);
  return prepared;
}

/// How many times each side of a ratio is timed, ShadeLab's rays and Embree alone alike: the
/// median is kept, so the first run's cold caches and page faults weigh on neither side.
constexpr int timedRuns = 5;

/// The shortest run that is timed on its own: a shorter pass over the rays (the bunny's point
/// light takes about 2 ms) is repeated within one run, and the run's time divided, so that
/// waking the threads and a moment's load on the machine weigh less. Without it, the ratios of
/// the bunny's point light moved from 0.62 to 0.80 between runs of the same binary.
constexpr double shortestTimedSeconds = 0.05;

/// The median over `runs` runs of the seconds that body(i) takes for every i in [0, count), in
/// a vtkSMPTools loop.
template<typename Body>
double medianParallelSeconds(int runs, std::size_t count, Body body)
{
  auto pass = [&]
  {
    vtkSMPTools::For(0, static_cast<vtkIdType>(count),
      [&](vtkIdType begin, vtkIdType end)
      {
        for (vtkIdType i = begin; i < end; ++i)
        {
          body(static_cast<std::size_t>(i));
        }
      });
  };
  // The first pass, untimed, warms the caches and says how many passes make a run.
  const double firstSeconds = medianMilliseconds(pass, 1, 1) / 1e3;
  const int passes = static_cast<int>(std::clamp(std::ceil(shortestTimedSeconds / firstSeconds), 1.0, 1000.0));
  auto run = [&]
  {
    for (int k = 0; k < passes; ++k)
    {
      pass();
    }
  };
  return medianMilliseconds(run, runs, runs) / 1e3 / passes;
}

/// The point light of the benchmark's shadows: above and to the side of the mesh.
glm::dvec3 lightOf(const RayMesh& mesh)
{
  return mesh.centre + mesh.radius * glm::dvec3(1.0, 2.0, 1.5);
}

/// Shadow rays per second, to the light from every vertex that faces it, in groups of
/// neighbouring vertices as the filter casts them.
double shadowRaysPerSecond(const RayMesh& mesh, std::size_t& rays)
{
  const glm::dvec3 light = lightOf(mesh);
  constexpr std::size_t group = rayVertexGroup;
  const std::size_t groups = (mesh.vertices.size() + group - 1) / group;
  const double seconds = medianParallelSeconds(timedRuns, groups,
    [&](std::size_t g)
    {
      const int count = static_cast<int>(std::min(group, mesh.vertices.size() - g * group));
      LightDirection directions[group];
      LightVisibility seen[group];
      for (int k = 0; k < count; ++k)
      {
        const glm::dvec3 d = light - mesh.vertices[g * group + k].position;
        directions[k] = { glm::normalize(d), glm::length(d) };
      }
      lightVisibility(*mesh.occluders, &mesh.vertices[g * group], directions, count, false, seen);
    });
  rays = 0;
  for (const RayVertex& v : mesh.vertices)
  {
    rays += glm::dot(light - v.position, v.normal) > 0 ? 1 : 0; // the vertices that cast one
  }
  return static_cast<double>(rays) / seconds;
}

/// Rays per second of Embree alone: the rays made beforehand, then traced in full packets of
/// 16 on every thread. What ShadeLab's rays per second would be if making a ray cost nothing.
double tracedRaysPerSecond(const RayMesh& mesh, const std::vector<OccluderMesh::FrameRay>& rays)
{
  constexpr std::size_t packet = OccluderMesh::bundleSize;
  const double seconds = medianParallelSeconds(timedRuns, (rays.size() + packet - 1) / packet,
    [&](std::size_t p)
    { mesh.occluders->occluded(&rays[p * packet], static_cast<int>(std::min(packet, rays.size() - p * packet))); });
  return static_cast<double>(rays.size()) / seconds;
}

/// The benchmark's shadow rays, from the vertices that face its light, in the BVH's frame.
std::vector<OccluderMesh::FrameRay> shadowFrameRays(const RayMesh& mesh)
{
  const glm::dvec3 light = lightOf(mesh);
  std::vector<OccluderMesh::FrameRay> rays;
  for (const RayVertex& v : mesh.vertices)
  {
    const glm::dvec3 d = light - v.position;
    if (glm::dot(d, v.normal) > 0)
    {
      rays.push_back(mesh.occluders->inFrame({ v.position, v.normal, glm::normalize(d), glm::length(d), v.id }));
    }
  }
  return rays;
}

/// Occlusion rays, `rays` stratified cosine-weighted directions from every stride-th vertex
/// with a normal, in the BVH's frame: like ambientOcclusion's (one sample to a cell rather
/// than two, which changes no ray's cost).
std::vector<OccluderMesh::FrameRay> occlusionFrameRays(const RayMesh& mesh, int rays, std::size_t stride)
{
  std::vector<OccluderMesh::FrameRay> frameRays;
  for (std::size_t i = 0; i < mesh.vertices.size(); i += stride)
  {
    const RayVertex& v = mesh.vertices[i];
    if (v.normal == glm::dvec3(0.0))
    {
      continue;
    }
    const SampleSequence samples(0, static_cast<std::uint64_t>(v.id), { rays, true });
    OccluderMesh::FrameRay ray = mesh.occluders->inFrame({ v.position, v.normal, {}, INFINITY, v.id });
    for (int j = 0; j < rays; ++j)
    {
      ray.direction = glm::vec3(cosineWeightedDirection(v.normal, samples.point(j)).direction);
      frameRays.push_back(ray);
    }
  }
  return frameRays;
}

/// A softbox: a square light as wide as the mesh's bounding radius, where the point light of
/// the shadows is, facing the mesh's centre; its exact estimator with `samples` shadow rays.
AreaLightEstimator softboxOf(const RayMesh& mesh, int samples)
{
  const glm::dvec3 centre = lightOf(mesh);
  const glm::dvec3 facing = glm::normalize(mesh.centre - centre);
  glm::dvec3 u, v;
  orthonormalBasis(facing, u, v); // u x v = facing: the square emits toward the mesh
  const glm::dvec3 halfU = 0.5 * mesh.radius * u, halfV = 0.5 * mesh.radius * v;
  AreaLight light;
  light.shape = PolygonEmitter{ { centre - halfU - halfV, centre + halfU - halfV, centre + halfU + halfV,
    centre - halfU + halfV } };
  light.sampling = { samples, true };
  return AreaLightEstimator(light, 0, LobeModel{});
}

/// The studio map with its shadows' directions by MIS and 64 stratified samples.
EnvironmentLight studioMapOf(const std::string& file)
{
  EnvironmentLight studio;
  try
  {
    studio.map = std::make_shared<const EnvironmentMap>(readEnvironmentMap(file));
  }
  catch (const std::runtime_error& error)
  {
    throw UserError(
      std::string(error.what()) + "; --visibility casts its shadows: run from the repository's top folder");
  }
  studio.file = file;
  studio.estimator = EnvironmentEstimator::MonteCarlo;
  studio.directions = EnvironmentDirections::Mis;
  studio.sampling = { 64, true };
  return studio;
}

SurfacePoint surfacePointOf(const RayVertex& vertex)
{
  return { vertex.position, vertex.normal, glm::dvec3(0.0), static_cast<std::uint64_t>(vertex.id) };
}

/// The seconds the shadow rays of an area light's or a map's samples from every stride-th
/// vertex take, cast as the visibility step casts them: in groups of neighbouring vertices
/// whose rays share packets.
double softShadowSeconds(const RayMesh& mesh, const ShadowedLightEstimator& light, std::size_t stride)
{
  const std::size_t count = (mesh.vertices.size() + stride - 1) / stride;
  const int words = hiddenSampleWords(light.shadowRayCount());
  std::vector<std::uint64_t> hidden(count * std::size_t(words));
  constexpr std::size_t group = rayVertexGroup;
  return medianParallelSeconds(timedRuns, (count + group - 1) / group,
    [&](std::size_t g)
    {
      HiddenSampleTracer tracer(*mesh.occluders);
      for (std::size_t k = g * group; k < std::min(count, (g + 1) * group); ++k)
      {
        const RayVertex& vertex = mesh.vertices[k * stride];
        tracer.add(light, surfacePointOf(vertex), vertex.id, &hidden[k * words]);
      }
      tracer.flush();
    });
}

/// The seconds that making the same rays takes, the light's shadowRays at every stride-th
/// vertex, without tracing them: the share of softShadowSeconds that is ShadeLab's own.
double rayMakingSeconds(const RayMesh& mesh, const ShadowedLightEstimator& light, std::size_t stride)
{
  return medianParallelSeconds(timedRuns, (mesh.vertices.size() + stride - 1) / stride,
    [&](std::size_t k)
    {
      thread_local std::vector<ShadowRay> rays;
      rays.resize(static_cast<std::size_t>(light.shadowRayCount()));
      light.shadowRays(surfacePointOf(mesh.vertices[k * stride]), rays.data());
    });
}

/// The same rays made beforehand in the BVH's frame, for Embree alone.
std::vector<OccluderMesh::FrameRay> softShadowFrameRays(
  const RayMesh& mesh, const ShadowedLightEstimator& light, std::size_t stride)
{
  std::vector<OccluderMesh::FrameRay> frameRays;
  std::vector<ShadowRay> rays(static_cast<std::size_t>(light.shadowRayCount()));
  for (std::size_t i = 0; i < mesh.vertices.size(); i += stride)
  {
    const RayVertex& v = mesh.vertices[i];
    light.shadowRays(surfacePointOf(v), rays.data());
    const OccluderMesh::FrameRay start = mesh.occluders->inFrame({ v.position, v.normal, {}, 0.0, v.id });
    for (const ShadowRay& ray : rays)
    {
      if (ray.cast)
      {
        frameRays.push_back({ start.origin, glm::vec3(ray.direction), mesh.occluders->frameDistance(ray.distance) });
      }
    }
  }
  return frameRays;
}

/// The same shadow rays with VTK's vtkStaticCellLocator, on one thread, over every stride-th
/// vertex: rays per second.
double locatorRaysPerSecond(const RayMesh& mesh, std::size_t stride, double& buildMilliseconds)
{
  vtkNew<vtkStaticCellLocator> locator;
  buildMilliseconds = medianMilliseconds(
    [&]
    {
      locator->SetDataSet(mesh.data);
      locator->Modified();
      locator->BuildLocator();
    },
    1, 1);
  const glm::dvec3 light = lightOf(mesh);
  std::size_t rays = 0;
  const auto start = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < mesh.vertices.size(); i += stride)
  {
    const RayVertex& v = mesh.vertices[i];
    if (glm::dot(light - v.position, v.normal) <= 0)
    {
      continue;
    }
    // From just off the surface, as the rays above start (1e-5 of the mesh's size).
    const glm::dvec3 from = v.position + 1e-5 * mesh.radius * v.normal;
    double p1[3] = { from.x, from.y, from.z }, p2[3] = { light.x, light.y, light.z };
    double t, x[3], pcoords[3];
    int subId;
    vtkIdType cellId;
    locator->IntersectWithLine(p1, p2, 0.0, t, x, pcoords, subId, cellId);
    ++rays;
  }
  return static_cast<double>(rays) / std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Ambient occlusion at every stride-th vertex with `settings`: its values, the rays drawn, and
/// the median seconds of `runs` runs.
struct OcclusionRun
{
  std::vector<double> values;
  double rays = 0; // per vertex, on average
  double seconds = 0;
};

OcclusionRun occlusionAt(const RayMesh& mesh, const OcclusionSettings& settings, std::size_t stride, int runs)
{
  OcclusionRun run;
  const std::size_t count = (mesh.vertices.size() + stride - 1) / stride;
  run.values.resize(count);
  std::vector<int> rays(count);
  run.seconds = medianParallelSeconds(runs, count,
    [&](std::size_t k)
    {
      const OcclusionEstimate ao = ambientOcclusion(*mesh.occluders, mesh.vertices[k * stride], settings);
      run.values[k] = ao.occlusion;
      rays[k] = ao.rays;
    });
  run.rays = std::accumulate(rays.begin(), rays.end(), 0.0) / static_cast<double>(count);
  return run;
}

OcclusionSettings fixedRays(int rays)
{
  OcclusionSettings settings;
  settings.sampling.samples = rays;
  return settings;
}

OcclusionSettings raysToTarget(double error)
{
  OcclusionSettings settings;
  settings.target = SamplingTarget::forFraction(error, 4096);
  return settings;
}

/// An estimate's errors against a reference: RMS, largest, and the fraction within `within`.
struct Errors
{
  double rms = 0, largest = 0, fractionWithin = 0;
};

Errors errorsOf(const std::vector<double>& values, const std::vector<double>& reference, double within = 0)
{
  Errors errors;
  double squares = 0;
  std::size_t inside = 0;
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    const double error = std::abs(values[i] - reference[i]);
    errors.largest = std::max(errors.largest, error);
    squares += error * error;
    inside += error <= within ? 1 : 0;
  }
  errors.rms = std::sqrt(squares / static_cast<double>(values.size()));
  errors.fractionWithin = static_cast<double>(inside) / static_cast<double>(values.size());
  return errors;
}

/// The seconds at which a ladder of runs (error falling as time rises) reaches `rms`: between
/// the two runs that bracket it, log time linear in log error. Infinity if none reaches it.
double secondsToReach(double rms, const std::vector<std::pair<double, double>>& secondsAndRms)
{
  for (std::size_t i = 1; i < secondsAndRms.size(); ++i)
  {
    const auto [t0, e0] = secondsAndRms[i - 1];
    const auto [t1, e1] = secondsAndRms[i];
    if (e1 <= rms && e0 > rms)
    {
      return std::exp(
        std::log(t0) + (std::log(t1) - std::log(t0)) * (std::log(rms) - std::log(e0)) / (std::log(e1) - std::log(e0)));
    }
  }
  return INFINITY;
}

/// The most that any split of the same rays among the vertices can save at equal RMS
/// (Neyman's allocation, docs/formulas.md section 13.7): mean(sigma^2) / mean(sigma)^2, with
/// each vertex's per-ray variance sigma^2 = AO (1 - AO) from the reference.
double neymanCeiling(const std::vector<double>& reference)
{
  double variance = 0, deviation = 0;
  for (const double ao : reference)
  {
    variance += ao * (1 - ao);
    deviation += std::sqrt(ao * (1 - ao));
  }
  const double n = static_cast<double>(reference.size());
  return (variance / n) / ((deviation / n) * (deviation / n));
}

/// The penumbra across a straight edge against its closed form (docs/formulas.md section 11.6):
/// a unit square light of radiance 1 at height 2 facing down, a plate at height 1 over x < 0.
/// From (x, 0, 0) the light's part q.x >= -x is seen: Lambert's formula on that rectangle.
ChartSpec penumbraChart(int samples)
{
  auto lightPart = [](double xFrom)
  {
    const double x0 = std::max(-0.5, xFrom);
    return std::vector<glm::dvec3>{ { x0, 0.5, 2 }, { 0.5, 0.5, 2 }, { 0.5, -0.5, 2 }, { x0, -0.5, 2 } };
  };
  const std::vector<glm::dvec3> plate = { { -50, -50, 1 }, { 0, -50, 1 }, { 0, 50, 1 }, { -50, 50, 1 } };
  const std::vector<PointId> offsets = { 0, 4 }, corners = { 0, 1, 2, 3 };
  const OccluderMesh occluders(
    PackedPoints<double>{ &plate[0].x }, plate.size(), { offsets.data(), corners.data(), 1 });
  ChartSeries closed{ "closed form", {}, {}, true, { 0, 0, 0 } };
  ChartSeries exact{ "exact, " + std::to_string(samples) + " samples", {}, {}, false, { 40, 40, 200 } };
  ChartSeries sampled{ "monte_carlo, " + std::to_string(samples) + " samples", {}, {}, false, { 200, 40, 40 } };
  AreaLight light;
  light.shape = PolygonEmitter{ lightPart(-0.5) };
  light.sampling = { samples, true };
  std::vector<std::uint64_t> words(std::size_t(hiddenSampleWords(samples)));
  for (int i = 0; i < 200; ++i)
  {
    const double x = -1 + 2 * (i + 0.5) / 200;
    const SurfacePoint point{ { x, 0, 0 }, { 0, 0, 1 }, { 0, 0, 1 }, std::uint64_t(i) };
    closed.x.push_back(x);
    closed.y.push_back(-x >= 0.5 ? 0.0 : polygonProjectedSolidAngle(lightPart(-x), point.position, point.normal));
    for (auto [estimator, series] :
      { std::pair{ AreaEstimator::Exact, &exact }, std::pair{ AreaEstimator::MonteCarlo, &sampled } })
    {
      light.estimator = estimator;
      const AreaLightEstimator estimate(light, 0, LobeModel{});
      hiddenSamples(occluders, estimate, point, -1, words.data());
      series->x.push_back(x);
      series->y.push_back(estimate.estimate(point, HiddenSamples{ words.data() }).irradiance.x);
    }
  }
  return { "Penumbra of a straight edge: a square light over a plate (" + std::to_string(samples) +
      " samples per receiver)",
    "receiver x (the plate's edge at 0; full shadow below -0.5, full light above 0.5)", "visible irradiance E / L",
    false, false, false, { closed, exact, sampled } };
}

void printRow(const std::string& label, double value, const std::string& unit, const std::string& note = "")
{
  std::cout << "  " << std::left << std::setw(44) << label << std::right << std::setw(10) << std::fixed
            << std::setprecision(2) << value << " " << std::left << std::setw(8) << unit << note << "\n";
}
}

void runRayBenchmark(const RayBenchmarkOptions& options)
{
  fs::create_directories(options.folder);
  const int threads = vtkSMPTools::GetEstimatedNumberOfThreads();
  std::ostringstream csv; // written at the end, whole or not at all
  csv << "mesh,vertices,triangles,quantity,value,unit\n";
  const vtkSmartPointer<vtkPolyData> clean = cleanBunny(options.bunnyFile);
  const EnvironmentLight studio = studioMapOf(options.envmapFile);
  std::vector<RayMesh> meshes;
  meshes.push_back(rayMesh("bunny", clean, options.repeats));
  meshes.push_back(rayMesh("bunny x64", bunnyOfAbout(clean, 2200000)->data, options.repeats));
  std::cout << "shadelab-bench --visibility: rays against the mesh's own triangles (Embree 3), " << threads
            << " threads\n";
  for (const RayMesh& mesh : meshes)
  {
    const std::size_t vertices = mesh.vertices.size();
    std::cout << mesh.name << ": " << vertices << " vertices, " << mesh.occluders->triangleCount() << " triangles\n";
    auto record = [&](const std::string& quantity, double value, const std::string& unit, const std::string& note = "")
    {
      printRow(quantity, value, unit, note);
      csv << csvText(mesh.name) << "," << vertices << "," << mesh.occluders->triangleCount() << "," << csvText(quantity)
          << "," << value << "," << csvText(unit) << "\n";
    };
    record("BVH build", mesh.buildMilliseconds, "ms");
    std::size_t shadowRays = 0;
    const double embree = shadowRaysPerSecond(mesh, shadowRays);
    record("shadow rays to a point light", embree / 1e6, "Mrays/s",
      std::to_string(shadowRays) + " rays, groups of " + std::to_string(rayVertexGroup) + " vertices");
    const std::size_t stride = std::max<std::size_t>(1, vertices / 2000);
    double locatorBuild = 0;
    const double vtk = locatorRaysPerSecond(mesh, stride, locatorBuild);
    record("  vtkStaticCellLocator build", locatorBuild, "ms");
    record("  vtkStaticCellLocator, one thread", vtk / 1e3, "krays/s",
      "IntersectWithLine, the same rays from every " + std::to_string(stride) + "th vertex");
    record("  Embree per core / VTK's locator", embree / threads / vtk, "x", "target 100");
    const double shadowCeiling = tracedRaysPerSecond(mesh, shadowFrameRays(mesh));
    record("  Embree alone, the same rays made beforehand", shadowCeiling / 1e6, "Mrays/s", "full packets of 16");
    record("  Embree alone per core / VTK's locator", shadowCeiling / threads / vtk, "x");
    record("  shadow rays / Embree alone", embree / shadowCeiling, "x", "target 0.9");
    // Ambient occlusion on every vertex of the bunny, every 16th of the large one.
    const std::size_t aoStride = vertices > 1000000 ? 16 : 1;
    double occlusion64Seconds = 0, occlusion64RaysPerSecond = 0;
    for (int rays : { 16, 64, 256 })
    {
      const OcclusionRun run = occlusionAt(mesh, fixedRays(rays), aoStride, timedRuns);
      const double seconds = run.seconds;
      const double cast = static_cast<double>(run.values.size()) * rays;
      if (rays == 64)
      {
        occlusion64Seconds = seconds;
        occlusion64RaysPerSecond = cast / seconds;
      }
      record("ambient occlusion, " + std::to_string(rays) + " rays: rays", cast / seconds / 1e6, "Mrays/s",
        "in packets of " + std::to_string(OccluderMesh::bundleSize));
      record("ambient occlusion, " + std::to_string(rays) + " rays: time", seconds * 1e3 * aoStride, "ms",
        aoStride > 1 ? "for the whole mesh, from every 16th vertex" : (rays == 64 ? "target 300 ms" : ""));
    }
    const double occlusionCeiling = tracedRaysPerSecond(mesh, occlusionFrameRays(mesh, 64, aoStride));
    record("ambient occlusion, Embree alone", occlusionCeiling / 1e6, "Mrays/s",
      "64 rays per vertex made beforehand, packets of 16");
    record("  ambient occlusion 64 / Embree alone", occlusion64RaysPerSecond / occlusionCeiling, "x", "target 0.9");
    // A shadowed softbox and the shadowed studio map, 64 samples: their rays as the visibility
    // step casts them.
    auto recordSoftShadows = [&](const std::string& name, const ShadowedLightEstimator& light, const char* timeTarget)
    {
      const std::vector<OccluderMesh::FrameRay> frameRays = softShadowFrameRays(mesh, light, aoStride);
      const std::size_t cast = frameRays.size(); // the rays cast: those whose sample carries light
      const double seconds = softShadowSeconds(mesh, light, aoStride);
      const double ceiling = tracedRaysPerSecond(mesh, frameRays);
      record(name + " shadows, 64 samples: rays", cast / seconds / 1e6, "Mrays/s",
        std::to_string(cast) + " rays cast, one per sample that can carry light");
      record(name + " shadows, 64 samples: time", seconds * 1e3 * aoStride, "ms",
        aoStride > 1 ? "for the whole mesh, from every 16th vertex" : "");
      record("  " + name + " / ambient occlusion 64, time", seconds / occlusion64Seconds, "x", timeTarget);
      record("  " + name + ", Embree alone", ceiling / 1e6, "Mrays/s", "the same rays made beforehand");
      record("  " + name + " / Embree alone", cast / seconds / ceiling, "x", "target 0.9");
      // Per cast ray and thread: where a ray's time goes.
      record("  " + name + ", making a ray", 1e9 * threads * rayMakingSeconds(mesh, light, aoStride) / cast, "ns",
        "per cast ray and thread, the rays made and not traced");
      record("  " + name + ", Embree alone, a ray", 1e9 * threads / ceiling, "ns", "per cast ray and thread");
    };
    recordSoftShadows("softbox", softboxOf(mesh, 64), "target 1.2");
    recordSoftShadows("studio map", EnvironmentLightEstimator(studio, 0, LobeModel{}), "");
  }

  // Error against time, fixed counts and rays to a target, against 4096 rays per vertex: on
  // every vertex of the bunny (chart 9), every 64th of the large one. Three runs of each (the
  // median), which keep the study to about a minute per mesh.
  constexpr int studyRuns = 3;
  for (const RayMesh& mesh : meshes)
  {
    const std::size_t stride = mesh.vertices.size() > 1000000 ? 64 : 1;
    const std::vector<double> reference = occlusionAt(mesh, fixedRays(4096), stride, 1).values;
    const std::size_t count = reference.size();
    auto recordStudy = [&](const std::string& quantity, double value, const std::string& unit)
    {
      csv << csvText(mesh.name) << "," << count << "," << mesh.occluders->triangleCount() << "," << quantity << ","
          << value << "," << unit << "\n";
    };
    std::cout << "ambient occlusion on the " << mesh.name << " against 4096 rays per vertex"
              << (stride > 1 ? ", every 64th vertex" : "") << ":\n";
    ChartSeries largest{ "largest error, fixed rays", {}, {}, true, { 200, 40, 40 }, true };
    ChartSeries rms{ "RMS error, fixed rays", {}, {}, true, { 40, 40, 200 }, true, true };
    ChartSeries largestToTarget{ "largest error, rays to a target", {}, {}, true, { 240, 140, 40 }, true };
    ChartSeries rmsToTarget{ "RMS error, rays to a target", {}, {}, true, { 40, 160, 160 }, true, true };
    std::vector<std::pair<double, double>> fixedLadder, targetLadder;
    for (int rays : { 4, 16, 64, 128, 192, 256, 384, 1024 })
    {
      const OcclusionRun run = occlusionAt(mesh, fixedRays(rays), stride, studyRuns);
      const Errors errors = errorsOf(run.values, reference);
      std::cout << "  " << std::setw(5) << rays << " rays: " << std::setprecision(1) << run.seconds * 1e3
                << " ms, largest error " << std::setprecision(4) << errors.largest << ", RMS " << errors.rms << "\n";
      recordStudy("ao_" + std::to_string(rays) + "_rays_ms", run.seconds * 1e3, "ms");
      recordStudy("ao_" + std::to_string(rays) + "_rays_largest_error", errors.largest, "");
      recordStudy("ao_" + std::to_string(rays) + "_rays_rms_error", errors.rms, "");
      largest.x.push_back(run.seconds * 1e3);
      largest.y.push_back(errors.largest);
      rms.x.push_back(run.seconds * 1e3);
      rms.y.push_back(errors.rms);
      fixedLadder.emplace_back(run.seconds, errors.rms);
    }
    for (double target : { 0.1, 0.05, 0.035, 0.03, 0.025, 0.02, 0.015, 0.01 })
    {
      const OcclusionRun run = occlusionAt(mesh, raysToTarget(target), stride, studyRuns);
      const Errors errors = errorsOf(run.values, reference, target);
      std::cout << "  to within " << std::setprecision(3) << target << ": " << std::setprecision(1) << run.seconds * 1e3
                << " ms, " << run.rays << " rays per vertex, largest error " << std::setprecision(4) << errors.largest
                << ", RMS " << errors.rms << ", " << std::setprecision(1) << 100 * errors.fractionWithin
                << "% within the target (95% asked)\n";
      const std::string name = "ao_within_" + std::to_string(target).substr(0, 5);
      recordStudy(name + "_ms", run.seconds * 1e3, "ms");
      recordStudy(name + "_rays_per_vertex", run.rays, "");
      recordStudy(name + "_rms_error", errors.rms, "");
      recordStudy(name + "_fraction_within", errors.fractionWithin, "");
      largestToTarget.x.push_back(run.seconds * 1e3);
      largestToTarget.y.push_back(errors.largest);
      rmsToTarget.x.push_back(run.seconds * 1e3);
      rmsToTarget.y.push_back(errors.rms);
      targetLadder.emplace_back(run.seconds, errors.rms);
    }
    const double fixedSeconds = secondsToReach(0.01, fixedLadder), targetSeconds = secondsToReach(0.01, targetLadder);
    std::cout << "  RMS 0.01: fixed rays in " << std::setprecision(1) << fixedSeconds * 1e3
              << " ms, rays to a target in " << targetSeconds * 1e3 << " ms: " << std::setprecision(2)
              << targetSeconds / fixedSeconds << "x (target 0.5); no split of the rays among the vertices can beat "
              << 1 / neymanCeiling(reference) << "x (Neyman)\n";
    recordStudy("ao_rms_0.01_to_a_target_over_fixed", targetSeconds / fixedSeconds, "x");
    recordStudy("ao_rms_neyman_floor", 1 / neymanCeiling(reference), "x");
    if (stride == 1)
    {
      ChartSpec chart{ "Ambient occlusion on the bunny against 4096 rays per vertex: fixed counts and rays to a target",
        "time for the mesh (ms)", "error in ambient_occlusion", true, true, true,
        { largest, rms, largestToTarget, rmsToTarget } };
      writeChartPng(chart, options.folder + "/9_ambient_occlusion.png");
    }
  }
  writeChartPng(penumbraChart(64), options.folder + "/10_penumbra.png");
  writeTextFile(options.folder + "/visibility.csv", csv.str());
  std::cout << "wrote " << options.folder << "/visibility.csv, 9_ambient_occlusion.png and 10_penumbra.png\n";
}
}
