#pragma once
// `shadelab-bench`: the filter's speed and memory on meshes from 10 thousand to 10 million
// vertices, against the baselines a user would otherwise have.
#include <string>
#include <vector>

namespace shadelab::app
{
struct BenchmarkOptions
{
  std::vector<long long> sizes{ 10000, 100000, 1000000, 10000000 };
  int maxRepeats = 9;
  std::string csvFile;
  std::string bunnyFile; // empty: spheres only
  /// Only the cases whose names contain one of these (all when empty).
  std::vector<std::string> caseFilters;
};

/// Prints the table to standard output as it goes and writes the CSV. Throws UserError.
void runBenchmark(const BenchmarkOptions& options);
}
