#pragma once
// `shadelab-bench --interreflection MESH`: interreflection's cost against ambient occlusion's on
// the same mesh and scene, in one process: 3 bounces of 64 gather rays per vertex against 64
// occlusion rays per vertex, their times and their peak memory, and the ratios (issue 46's
// targets: at most 2 times the time, at most 1.5 times the peak).
#include <string>

namespace shadelab::app
{
struct InterreflectionBenchmarkOptions
{
  std::string mesh;
  std::string scene = "data/scenes/studio.json";
  int repeats = 1;
};

/// Prints both runs and their ratios to standard output. Throws UserError.
void runInterreflectionBenchmark(const InterreflectionBenchmarkOptions& options);
}
