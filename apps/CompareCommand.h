#pragma once
// shadelab compare BASELINE RESULT: two files' arrays value by value, for regression tests
// on mesh scalars (docs/guide/regression-tests.md).
#include <CLI/CLI.hpp>

#include <optional>
#include <string>
#include <vector>

namespace shadelab::app
{
struct CompareOptions
{
  std::string baseline, result;
  std::vector<std::string> absolute, relative, ulps; // rules: "PATTERN:VALUE" or "VALUE"
  std::vector<std::string> arrays{ "*" };            // the arrays to compare, by wildcard
  std::vector<std::string> exclude;
  std::vector<std::string> flagArrays{ "*shading_flags" }; // integers whose bits are ShadeLab's flags
  std::optional<double> standardErrors;                    // statistical mode: k
  std::optional<double> significance;                      // statistical mode: alpha (default 0.001)
  bool noPoints = false;
  std::optional<double> nearest; // match by nearest point within this distance, not by id
  std::string json, junit, diff; // report files, and the difference mesh
};

CLI::App* addCompareCommand(CLI::App& cli, CompareOptions& options);

/// Exit codes: 0 the files agree, 1 they differ, 2 a file cannot be read or an option is wrong.
int runCompare(const CompareOptions& options);
}
