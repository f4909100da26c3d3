#include "CompareCommand.h"

#include "CompareMatching.h"
#include "CompareReports.h"
#include "ComparedArrays.h"
#include "ComparedPieces.h"
#include "MeshFiles.h"
#include "RunWarnings.h"

#include "ToleranceRules.h"
#include "ValueComparison.h"

#include "vtkPolyData.h"

#include <algorithm>
#include <cmath>
#include <iostream>

namespace shadelab::app
{
namespace
{
using namespace compare;

/// Whether name matches one of the wildcard patterns.
bool matchesAny(const std::vector<std::string>& patterns, const std::string& name)
{
  return std::any_of(patterns.begin(), patterns.end(), [&](const std::string& p) { return wildcardMatches(p, name); });
}

/// The statistical mode's chance that two honest runs fail, for an array.
constexpr double defaultSignificance = 0.001;

/// The tolerance rules of the command line, parsed.
struct Rules
{
  PatternRules<ToleranceValue> absolute, relative;
  PatternRules<long long> ulps;

  std::optional<double> standardErrors;
  double significance = defaultSignificance;

  /// The rule for an array of the baseline.
  ValueRule ruleFor(const FileArray& array) const
  {
    ValueRule rule;
    const double range = array.values.range();
    rule.absolute = absolute.find(array.name).value_or(ToleranceValue{}).of(range);
    const std::optional<ToleranceValue> given = relative.find(array.name);
    rule.relative = given ? given->of(range) : defaultRelativeTolerance(array.values.type);
    rule.ulps = ulps.find(array.name);
    rule.standardErrors = standardErrors;
    rule.significance = significance;
    return rule;
  }
};

/// --atol, --rtol and --ulps as rules, with the statistical mode's settings, checked.
Rules parseRules(const CompareOptions& options)
{
  Rules rules;
  try
  {
    for (const std::string& text : options.absolute)
    {
      const auto [pattern, value] = splitRule(text);
      rules.absolute.add(pattern, parseToleranceValue(value));
    }
    for (const std::string& text : options.relative)
    {
      const auto [pattern, value] = splitRule(text);
      const ToleranceValue tolerance = parseToleranceValue(value);
      if (tolerance.timesRange)
      {
        throw UserError("--rtol '" + text +
          "': a relative tolerance is a plain number (a fraction of the values); "
          "a tolerance relative to the range is --atol's");
      }
      rules.relative.add(pattern, tolerance);
    }
    for (const std::string& text : options.ulps)
    {
      const auto [pattern, value] = splitRule(text);
      rules.ulps.add(pattern, parseUlps(value));
    }
  }
  catch (const std::invalid_argument& error)
  {
    throw UserError(error.what());
  }
  if (options.standardErrors && !(*options.standardErrors > 0 && std::isfinite(*options.standardErrors)))
  {
    throw UserError("--standard-errors must be a number > 0 (3 is usual)");
  }
  if (options.significance && !options.standardErrors)
  {
    throw UserError("--significance is the statistical mode's: give --standard-errors K with it (3 is usual)");
  }
  // Each check's share stays far above the 1.4e-65 the binomial quantile leaves out.
  if (options.significance && !(*options.significance >= 1e-12 && *options.significance <= 0.5))
  {
    throw UserError("--significance must be a number from 1e-12 to 0.5 (0.001 is usual)");
  }
  rules.standardErrors = options.standardErrors;
  rules.significance = options.significance.value_or(defaultSignificance);
  return rules;
}

/// Each report file's folder and extension, before the slow work.
void checkOutputFiles(const CompareOptions& options)
{
  if (!options.json.empty())
  {
    checkOutputFile(options.json, { ".json" });
  }
  if (!options.junit.empty())
  {
    checkOutputFile(options.junit, { ".xml" });
  }
  if (!options.diff.empty())
  {
    checkOutputFile(options.diff, meshExtensions);
  }
}

/// Whether --arrays selects the array of this name and --exclude leaves it in.
bool isSelected(const CompareOptions& options, const std::string& name)
{
  return matchesAny(options.arrays, name) && !matchesAny(options.exclude, name);
}

/// Both files read, their arrays listed (those --arrays and --exclude leave out dropped from
/// the not-numbers lists) and, with --nearest, their points matched.
ComparedFiles readFiles(const CompareOptions& options, RunWarnings& warnings)
{
  ComparedFiles files;
  OrderedDataSet baseline = inGlobalIdOrder(readDataSet(options.baseline), options.baseline);
  warnings.collect(options.baseline);
  OrderedDataSet result = inGlobalIdOrder(readDataSet(options.result), options.result);
  warnings.collect(options.result);
  files.baselineData = baseline.data;
  files.baselineOrder = baseline.description;
  files.resultData = result.data;
  files.resultOrder = result.description;
  files.baseline = arraysOf(files.baselineData, !options.noPoints, files.skippedBaseline);
  files.result = arraysOf(files.resultData, !options.noPoints, files.skippedResult);
  if (options.nearest)
  {
    if (!(*options.nearest >= 0))
    {
      throw UserError("--nearest must be a distance >= 0");
    }
    files.matching = matchByNearest(files.baselineData, files.resultData, files.result, *options.nearest);
  }
  for (const std::string& pattern : options.arrays)
  {
    auto matches = [&](const FileArray& array) { return wildcardMatches(pattern, array.name); };
    if (std::none_of(files.baseline.begin(), files.baseline.end(), matches) &&
      std::none_of(files.result.begin(), files.result.end(), matches))
    {
      throw UserError("--arrays '" + pattern + "' matches no array of either file");
    }
  }
  if (!options.diff.empty() && !vtkPolyData::SafeDownCast(files.resultData))
  {
    throw UserError(std::string("--diff writes a mesh (.vtp or .vtk), and the result is a ") +
      files.resultData->GetClassName() + ": leave --diff out for it");
  }
  for (std::vector<SkippedArray>* skipped : { &files.skippedBaseline, &files.skippedResult })
  {
    skipped->erase(std::remove_if(skipped->begin(), skipped->end(),
                     [&](const SkippedArray& a) { return !isSelected(options, a.name); }),
      skipped->end());
  }
  return files;
}

/// Why the baseline's array and the result's of the same name cannot be compared value by
/// value, or "" when they can.
std::string pairingProblem(
  const FileArray& array, const FileArray* other, const ComparedFiles& files, const CompareOptions& options)
{
  const ArrayValues& a = array.values;
  if (!other)
  {
    return std::string("missing from ") + options.result;
  }
  const std::string& unmatched = files.matching.problemOf(array.association);
  if (!unmatched.empty())
  {
    return "not compared: " + unmatched;
  }
  if (other->values.type != a.type)
  {
    return std::string(typeName(a.type)) + " in " + options.baseline + ", " + typeName(other->values.type) + " in " +
      options.result;
  }
  if (other->values.components != a.components)
  {
    return std::to_string(a.components) + " components in " + options.baseline + ", " +
      std::to_string(other->values.components) + " in " + options.result;
  }
  if (other->values.tuples() != a.tuples())
  {
    return std::to_string(a.tuples()) + " tuples in " + options.baseline + ", " +
      std::to_string(other->values.tuples()) + " in " + options.result;
  }
  return "";
}

/// The baseline's array judged against the result's of the same name, with its rule and,
/// with --standard-errors, both files' NAME_std_error where they hold them.
ArrayReport compareArray(
  const FileArray& array, const ComparedFiles& files, const Rules& rules, const CompareOptions& options)
{
  ArrayReport report;
  report.baseline = &array;
  report.name = array.name;
  report.association = array.association;
  report.flags = array.values.type == ValueType::Integer && matchesAny(options.flagArrays, array.name);
  const FileArray* other = findArray(files.result, array.name, array.association);
  report.problem = pairingProblem(array, other, files, options);
  if (!report.problem.empty())
  {
    return report;
  }
  const ArrayValues& a = array.values;
  report.rule = rules.ruleFor(array);
  const FileArray* errorsA = findArray(files.baseline, array.name + "_std_error", array.association);
  const FileArray* errorsB = findArray(files.result, array.name + "_std_error", array.association);
  const bool statistical = options.standardErrors && errorsA && errorsB && errorsA->values.type != ValueType::Integer &&
    errorsB->values.type != ValueType::Integer && errorsA->values.size() == a.size() &&
    errorsB->values.size() == a.size();
  if (!statistical)
  {
    report.rule.standardErrors.reset();
  }
  report.difference = compareArrays(
    a, other->values, report.rule, statistical ? &errorsA->values : nullptr, statistical ? &errorsB->values : nullptr);
  return report;
}

/// One report per selected array: each of the baseline's, then those only in the result.
std::vector<ArrayReport> pairArrays(const ComparedFiles& files, const Rules& rules, const CompareOptions& options)
{
  auto selected = [&](const FileArray& array)
  { return array.association == Association::Points || isSelected(options, array.name); };
  std::vector<ArrayReport> reports;
  for (const FileArray& array : files.baseline)
  {
    if (selected(array))
    {
      reports.push_back(compareArray(array, files, rules, options));
    }
  }
  for (const FileArray& array : files.result)
  {
    if (selected(array) && !findArray(files.baseline, array.name, array.association))
    {
      ArrayReport report;
      report.name = array.name;
      report.association = array.association;
      report.problem = std::string("not in ") + options.baseline;
      reports.push_back(std::move(report));
    }
  }
  return reports;
}

/// The reports asked for by --json, --junit and --diff.
void writeReports(
  const std::vector<ArrayReport>& reports, bool passed, const ComparedFiles& files, const CompareOptions& options)
{
  if (!options.json.empty())
  {
    writeTextFile(options.json, jsonReport(reports, passed, files, options));
  }
  if (!options.junit.empty())
  {
    writeTextFile(options.junit, junitReport(reports, files, options));
  }
  if (!options.diff.empty())
  {
    // readFiles has made sure that the result is a mesh.
    writeMesh(
      differenceMesh(vtkPolyData::SafeDownCast(files.resultData), reports, files), options.diff, Compression::LZ4);
  }
}
}

CLI::App* addCompareCommand(CLI::App& cli, CompareOptions& options)
{
  CLI::App* command = cli.add_subcommand("compare",
    "Compare two files' arrays value by value, for regression tests: point, cell and field data and the "
    "points, each value passing when |a - b| <= max(rtol * max(|a|, |b|), atol), or Monte Carlo arrays judged "
    "as noise by their standard errors (--standard-errors). Exit code 0 when they agree, 1 "
    "when they differ, 2 when a file cannot be read or an option is wrong.");
  command
    ->add_option("baseline", options.baseline,
      "the file to compare against (.vtp, .pvtp, .vtu, .vti, .vts, .vtr, .vtk, .ply, .obj, .stl); a mesh whose "
      "points have global ids (a .pvtp's pieces) is compared in their order, each point once")
    ->required();
  command->add_option("result", options.result, "the file to judge")->required();
  // One value to each occurrence (repeat the option for more), so that an option before the
  // files does not take them as its values.
  command
    ->add_option("--atol", options.absolute,
      "absolute tolerance, for every array (1e-6) or by name with wildcards ('total:1e-6', '*_cos_incidence:1e-7'), "
      "or relative to the baseline array's range ('1e-3*range'); the last rule that matches wins; default 0")
    ->allow_extra_args(false);
  command
    ->add_option("--rtol", options.relative,
      "relative tolerance, a number, for every array or by name as --atol; default 4 units in the last place of the "
      "array's type "
      "(4.8e-7 for float32, 8.9e-16 for float64)")
    ->allow_extra_args(false);
  command
    ->add_option("--ulps", options.ulps,
      "judge floating-point values by units in the last place instead ('3', 'total:4'): pass when at most that many "
      "numbers of the array's type apart; where a ULP rule matches, it replaces --atol and --rtol")
    ->allow_extra_args(false);
  command
    ->add_option("--standard-errors", options.standardErrors,
      "statistical mode, for Monte Carlo arrays: where both files hold NAME_std_error beside NAME, NAME's values "
      "are judged together as noise, component by component: the count of values outside K combined standard "
      "errors sqrt(e_a^2 + e_b^2) must be at most the Binomial(n, 2 P(Z > K)) quantile, and the mean difference "
      "within the normal quantile times its standard error sqrt(sum of e_a^2 + e_b^2) / n; values whose standard "
      "errors are both 0 must pass --atol and --rtol. 3 is usual")
    ->type_name("K");
  command
    ->add_option("--significance", options.significance,
      "with --standard-errors: the chance that two honest runs fail, for an array; shared equally by the count and "
      "the mean difference of each component (Bonferroni); from 1e-12 to 0.5, default 0.001")
    ->type_name("ALPHA");
  command
    ->add_option("--arrays", options.arrays, "compare only the arrays whose names match these wildcards (default *)")
    ->delimiter(',')
    ->allow_extra_args(false);
  command->add_option("--exclude", options.exclude, "leave out the arrays whose names match these wildcards")
    ->delimiter(',')
    ->allow_extra_args(false);
  command
    ->add_option("--flags", options.flagArrays,
      "integer arrays whose bits are ShadeLab's shading flags, named in the report (default *shading_flags)")
    ->delimiter(',')
    ->allow_extra_args(false);
  command->add_flag("--no-points", options.noPoints, "do not compare the point coordinates");
  command->add_option("--nearest", options.nearest,
    "match the result's points to the baseline's by nearest point within this distance, and its cells by their "
    "centres, instead of by id (for meshes whose points were re-ordered)");
  command->add_option("--json", options.json, "also write the report as JSON to this file");
  command->add_option("--junit", options.junit,
    "also write the report as JUnit XML to this file (.xml), one test case per array, for CI systems");
  command->add_option("--diff", options.diff,
    "also write the result's mesh (.vtp or .vtk) with NAME_difference (result - baseline) for each array compared "
    "and compare_passed (1 where every compared value of a point or cell passes, 0 where one fails or, in statistical "
    "mode, lies outside K standard errors), to open in ParaView");
  return command;
}

int runCompare(const CompareOptions& options)
{
  RunWarnings warnings; // a reader's warning says the file is damaged: its values may be too
  ComparedFiles files;
  std::vector<ArrayReport> reports;
  try
  {
    const Rules rules = parseRules(options);
    checkOutputFiles(options);
    files = readFiles(options, warnings);
    reports = pairArrays(files, rules, options);
  }
  catch (const UserError& error)
  {
    std::cerr << "shadelab compare: " << error.what() << "\n";
    return 2;
  }
  if (reports.empty())
  {
    std::cerr << "shadelab compare: no array to compare (see --arrays, --exclude and --no-points)\n";
    return 2;
  }
  const bool passed = printReports(reports, files, options);
  warnings.show();
  try
  {
    writeReports(reports, passed, files, options);
  }
  catch (const std::exception& error)
  {
    std::cerr << "shadelab compare: " << error.what() << "\n";
    return 2;
  }
  return passed ? 0 : 1;
}
}
