#include "InterreflectionBenchmark.h"

#include "BenchmarkMeshes.h"
#include "MemoryProbe.h"
#include "MeshFiles.h"

#include "SceneFile.h"

#include "vtkPolyData.h"

#include <algorithm>
#include <chrono>
#include <iomanip>
#include <iostream>
#include <malloc.h>
#include <vector>

namespace shadelab::app
{
namespace
{
/// One run's seconds and the process's peak resident bytes during it.
struct RunCost
{
  double seconds = 0;
  double peakBytes = 0;
};

/// The filter run on the mesh under the scene, its output dropped: what it cost. The peak is
/// reset first, after the heap's free pages are handed back, so that what the run before it
/// left behind does not count.
RunCost shadeOnce(vtkPolyData* mesh, const Scene& scene)
{
  malloc_trim(0);
  if (!resetPeakMemory())
  {
    throw UserError("this kernel does not let the peak memory be reset (/proc/self/clear_refs): no peak to measure");
  }
  const auto start = std::chrono::steady_clock::now();
  shaded(mesh, scene); // dropped at once
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
  return { elapsed.count(), double(statusBytes("VmHWM").value_or(0)) };
}

double median(std::vector<double> values)
{
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

void printRow(const char* name, const std::vector<RunCost>& runs, RunCost& medians)
{
  std::vector<double> seconds, peaks;
  for (const RunCost& run : runs)
  {
    seconds.push_back(run.seconds);
    peaks.push_back(run.peakBytes);
  }
  medians = { median(seconds), median(peaks) };
  std::cout << "  " << std::left << std::setw(44) << name << std::right << std::fixed << std::setprecision(2)
            << std::setw(8) << medians.seconds << " s" << std::setw(8) << medians.peakBytes / 1e9 << " GB peak\n";
}
}

void runInterreflectionBenchmark(const InterreflectionBenchmarkOptions& options)
{
  const vtkSmartPointer<vtkPolyData> mesh = readMesh(options.mesh);
  const Scene scene = readSceneFile(options.scene);
  Scene occlusion = scene;
  occlusion.interreflection.reset();
  occlusion.ambientOcclusion = AmbientOcclusion{};
  Scene bounces = scene;
  bounces.ambientOcclusion.reset();
  bounces.interreflection = Interreflection{ 3, { 64, true } };
  std::cout << "shadelab-bench --interreflection: " << options.mesh << " (" << mesh->GetNumberOfPoints()
            << " vertices) under " << options.scene << ", " << options.repeats
            << " round(s), each run in turn (medians; the peak is the process's, the mesh included)\n";
  std::vector<RunCost> occlusionRuns, bounceRuns;
  for (int round = 0; round < options.repeats; ++round)
  {
    occlusionRuns.push_back(shadeOnce(mesh, occlusion));
    bounceRuns.push_back(shadeOnce(mesh, bounces));
  }
  RunCost ambient, indirect;
  printRow("ambient occlusion, 64 rays per vertex", occlusionRuns, ambient);
  printRow("interreflection, 3 bounces of 64 gather rays", bounceRuns, indirect);
  std::cout << std::setprecision(2) << "  interreflection / ambient occlusion: time "
            << indirect.seconds / ambient.seconds << " (target at most 2), peak memory "
            << indirect.peakBytes / ambient.peakBytes << " (target at most 1.5)\n";
}
}
