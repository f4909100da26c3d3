#include "CompareReports.h"

#include "NoiseTest.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <utility>

namespace shadelab::app::compare
{
namespace
{
/// A double as JSON: a number where finite, else its text ("nan", "inf"), which JSON has no
/// number for.
nlohmann::json jsonNumber(double x)
{
  return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(exact(x));
}

/// The statistical mode's checks: its parameters, then each component's counts and mean
/// difference.
nlohmann::json noiseJson(const ArrayReport& report)
{
  const ArrayDifference& d = *report.difference;
  nlohmann::json components = nlohmann::json::array();
  for (std::size_t component = 0; component < d.noise.size(); ++component)
  {
    const NoiseCheck& check = d.noise[component];
    components.push_back({ { "component", component }, { "values", check.values }, { "outside", check.outside },
      { "expected", check.expected }, { "allowed", check.allowed }, { "mean_difference", check.meanDifference },
      { "mean_difference_standard_error", check.meanDifferenceError },
      { "mean_difference_limit", check.meanDifferenceLimit }, { "count_passed", check.countPasses() },
      { "bias_passed", check.biasPasses() } });
  }
  return { { "k", *report.rule.standardErrors }, { "significance", report.rule.significance },
    { "significance_per_check", significancePerCheck(report.rule.significance, report.baseline->values.components) },
    { "exact_values", d.exactValues }, { "components", components } };
}

/// An array's entry of the report.
nlohmann::json jsonOf(
  const ArrayReport& report, const std::vector<FileArray>& baseline, const std::vector<FileArray>& result)
{
  nlohmann::json entry = { { "name", report.name }, { "data", associationName(report.association) },
    { "passed", report.passes() } };
  if (report.baseline)
  {
    entry["type"] = typeName(report.baseline->values.type);
    entry["components"] = report.baseline->values.components;
  }
  if (!report.problem.empty())
  {
    entry["problem"] = report.problem;
    return entry;
  }
  const ArrayDifference& d = *report.difference;
  entry["values"] = d.values;
  entry["failing"] = d.failing;
  entry["max_difference"] = jsonNumber(d.largest);
  entry["rms"] = jsonNumber(d.rms());
  entry["l2"] = jsonNumber(d.l2());
  entry["nan_in_both"] = d.nanInBoth;
  entry["nan_in_one"] = d.nanInOne;
  entry["rule"] = report.rule.ulps
    ? nlohmann::json{ { "ulps", *report.rule.ulps } }
    : nlohmann::json{ { "absolute", report.rule.absolute }, { "relative", report.rule.relative } };
  if (d.worst && d.largest > 0)
  {
    const FileArray* other = findArray(result, report.name, report.association);
    const std::size_t components = static_cast<std::size_t>(report.baseline->values.components);
    auto value = [](const ArrayValues& values, std::size_t i)
    { return values.type == ValueType::Integer ? nlohmann::json(values.integers[i]) : jsonNumber(values.reals[i]); };
    entry["worst"] = { { "tuple", *d.worst / components }, { "component", *d.worst % components },
      { "where", placeOf(report, *d.worst, baseline) }, { "baseline", value(report.baseline->values, *d.worst) },
      { "result", value(other->values, *d.worst) } };
  }
  if (report.baseline->values.type == ValueType::Integer)
  {
    nlohmann::json bits = nlohmann::json::array();
    for (int bit = 0; bit < 64; ++bit)
    {
      if (d.bitCounts[static_cast<std::size_t>(bit)] > 0)
      {
        bits.push_back({ { "bit", bit }, { "name", bitName(bit, report.flags) },
          { "values", d.bitCounts[static_cast<std::size_t>(bit)] } });
      }
    }
    entry["bits_that_differ"] = bits;
  }
  if (report.rule.standardErrors)
  {
    entry["standard_errors"] = { { "k", *report.rule.standardErrors }, { "values", d.withStandardError },
      { "within_1", d.withinStandardErrors[0] }, { "within_2", d.withinStandardErrors[1] },
      { "within_3", d.withinStandardErrors[2] } };
    entry["noise"] = noiseJson(report);
  }
  return entry;
}
}

std::string jsonReport(
  const std::vector<ArrayReport>& reports, bool passed, const ComparedFiles& files, const CompareOptions& options)
{
  // How each file's points and cells were put in the order compared (ComparedPieces.h).
  auto order = [](const std::string& description) { return description.empty() ? "as read" : description; };
  nlohmann::json report = { { "baseline", options.baseline }, { "result", options.result }, { "passed", passed },
    { "baseline_order", order(files.baselineOrder) }, { "result_order", order(files.resultOrder) },
    { "arrays", nlohmann::json::array() }, { "not_compared", nlohmann::json::array() },
    { "not_compared_in_result", nlohmann::json::array() } };
  for (const ArrayReport& r : reports)
  {
    report["arrays"].push_back(jsonOf(r, files.baseline, files.result));
  }
  for (const auto& [key, skipped] : { std::pair{ "not_compared", &files.skippedBaseline },
         std::pair{ "not_compared_in_result", &files.skippedResult } })
  {
    for (const SkippedArray& array : *skipped)
    {
      report[key].push_back(array.description);
    }
  }
  // Names that are not UTF-8 (a legacy file may hold any bytes) with U+FFFD for each bad byte.
  return report.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}
}
