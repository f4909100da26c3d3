#include "CompareCommand.h"

#include "MeshFiles.h"
#include "RunWarnings.h"

#include "NoiseTest.h"
#include "NumberText.h"
#include "ShadingFlags.h"
#include "ToleranceRules.h"
#include "ValueComparison.h"

#include "vtkArrayDispatch.h"
#include "vtkCellCenters.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDataArrayRange.h"
#include "vtkDataSet.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdList.h"
#include "vtkMath.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStaticPointLocator.h"
#include "vtkTypeInt64Array.h"
#include "vtkUnsignedCharArray.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>
#include <type_traits>

namespace shadelab::app
{
namespace
{
/// Where an array lives in a dataset.
enum class Association
{
  Points,
  PointData,
  CellData,
  FieldData,
};

const char* associationName(Association association)
{
  switch (association)
  {
    case Association::Points: return "points";
    case Association::PointData: return "point";
    case Association::CellData: return "cell";
    case Association::FieldData: break;
  }
  return "field";
}

/// An array of one file, its values copied out.
struct FileArray
{
  std::string name;
  Association association = Association::PointData;
  ArrayValues values;
};

const char* typeName(ValueType type)
{
  switch (type)
  {
    case ValueType::Float32: return "float32";
    case ValueType::Float64: return "float64";
    case ValueType::Integer: break;
  }
  return "integer";
}

/// Copies a VTK array's values: integers exactly (as 64-bit), floating-point ones as doubles.
struct CopyValues
{
  ArrayValues& out;

  template<typename Array>
  void operator()(Array* array)
  {
    using Value = vtk::GetAPIType<Array>;
    const auto range = vtk::DataArrayValueRange(array);
    if constexpr (std::is_integral_v<Value>)
    {
      out.integers.assign(range.begin(), range.end());
    }
    else
    {
      out.reals.assign(range.begin(), range.end());
    }
  }
};

ArrayValues valuesOf(vtkDataArray* array)
{
  ArrayValues values;
  const int type = array->GetDataType();
  values.type = type == VTK_FLOAT ? ValueType::Float32 : type == VTK_DOUBLE ? ValueType::Float64 : ValueType::Integer;
  values.components = array->GetNumberOfComponents();
  CopyValues copy{ values };
  if (!vtkArrayDispatch::Dispatch::Execute(array, copy))
  {
    // Arrays the dispatcher does not know (bits, say), through the generic interface.
    const auto range = vtk::DataArrayValueRange(array);
    if (values.type == ValueType::Integer)
    {
      for (const double v : range)
      {
        values.integers.push_back(static_cast<std::int64_t>(v));
      }
    }
    else
    {
      values.reals.assign(range.begin(), range.end());
    }
  }
  return values;
}

/// An array that is not numbers (text, say): its name, and what it is.
struct SkippedArray
{
  std::string name, description;
};

/// The dataset's point coordinates and its numeric arrays; the arrays it holds that are not
/// numbers go to skipped.
std::vector<FileArray> arraysOf(vtkDataSet* data, bool withPoints, std::vector<SkippedArray>& skipped)
{
  std::vector<FileArray> arrays;
  if (withPoints)
  {
    FileArray points{ "points", Association::Points, {} };
    auto* pointSet = vtkPointSet::SafeDownCast(data);
    if (pointSet && pointSet->GetPoints())
    {
      points.values = valuesOf(pointSet->GetPoints()->GetData());
    }
    else
    {
      // Implicit points (an image, a rectilinear grid), as VTK computes them.
      points.values.components = 3;
      for (vtkIdType i = 0; i < data->GetNumberOfPoints(); ++i)
      {
        double p[3];
        data->GetPoint(i, p);
        points.values.reals.insert(points.values.reals.end(), p, p + 3);
      }
    }
    arrays.push_back(std::move(points));
  }
  const std::pair<Association, vtkFieldData*> groups[] = { { Association::PointData, data->GetPointData() },
    { Association::CellData, data->GetCellData() }, { Association::FieldData, data->GetFieldData() } };
  for (const auto& [association, group] : groups)
  {
    for (int i = 0; group && i < group->GetNumberOfArrays(); ++i)
    {
      vtkAbstractArray* array = group->GetAbstractArray(i);
      const std::string name = array->GetName() && *array->GetName()
        ? array->GetName()
        : std::string("(unnamed ") + associationName(association) + " array " + std::to_string(i) + ")";
      auto* numbers = vtkDataArray::SafeDownCast(array);
      if (!numbers)
      {
        skipped.push_back(
          { name, name + " (" + associationName(association) + " data, " + array->GetClassName() + ")" });
        continue;
      }
      arrays.push_back({ name, association, valuesOf(numbers) });
    }
  }
  return arrays;
}

bool matchesAny(const std::vector<std::string>& patterns, const std::string& name)
{
  return std::any_of(patterns.begin(), patterns.end(), [&](const std::string& p) { return wildcardMatches(p, name); });
}

const FileArray* find(const std::vector<FileArray>& arrays, const std::string& name, Association association)
{
  for (const FileArray& array : arrays)
  {
    if (array.name == name && array.association == association)
    {
      return &array;
    }
  }
  return nullptr;
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

/// One array's verdict.
struct ArrayReport
{
  const FileArray* baseline = nullptr;
  std::string name;
  Association association = Association::PointData;
  std::string problem; // why it could not be compared
  ValueRule rule;
  std::optional<ArrayDifference> difference;
  bool flags = false;

  bool passes() const { return problem.empty() && difference && difference->passes(); }
};

/// What a person reads: a number with few digits; and one with all of them.
std::string brief(double x)
{
  return withDigits(x, 3);
}

std::string exact(double x)
{
  return withDigits(x, 17);
}

std::string valueText(const ArrayValues& values, std::size_t i)
{
  return values.type == ValueType::Integer ? std::to_string(values.integers[i]) : exact(values.reals[i]);
}

/// The rule a value passes by itself: "atol 0, rtol 4.77e-07", "within 4 ULP", "equal".
std::string toleranceText(const ArrayReport& report)
{
  if (report.baseline->values.type == ValueType::Integer)
  {
    return "equal";
  }
  return report.rule.ulps ? "within " + std::to_string(*report.rule.ulps) + " ULP"
                          : "atol " + brief(report.rule.absolute) + ", rtol " + brief(report.rule.relative);
}

std::string ruleText(const ArrayReport& report)
{
  std::string text = toleranceText(report);
  if (report.rule.standardErrors)
  {
    text += "; noise: " + brief(*report.rule.standardErrors) + " standard errors, significance " +
      brief(report.rule.significance);
  }
  return text;
}

/// One component's noise checks in words, each that fails saying why.
std::string noiseText(const NoiseCheck& check, double k)
{
  if (check.values == 0)
  {
    return "no value with a standard error > 0";
  }
  return std::to_string(check.outside) + " of " + std::to_string(check.values) + " values outside " + brief(k) +
    " standard errors (" + brief(check.expected) + " expected, at most " + std::to_string(check.allowed) + " allowed" +
    (check.countPasses() ? "" : ": too many") + "); mean difference " + brief(check.meanDifference) + " (at most " +
    brief(check.meanDifferenceLimit) + " either way" + (check.biasPasses() ? "" : ": a bias") + ")";
}

/// "noise: ..." for an array of one component, "noise of component 1: ..." for the others.
std::string noiseLine(const ArrayReport& report, std::size_t component)
{
  const bool several = report.baseline->values.components > 1;
  return (several ? "noise of component " + std::to_string(component) + ": " : std::string("noise: ")) +
    noiseText(report.difference->noise[component], *report.rule.standardErrors);
}

/// Where value i of the array is: "point 12 (x, y, z), component 1".
std::string placeOf(const ArrayReport& report, std::size_t i, const std::vector<FileArray>& baseline)
{
  const ArrayValues& values = report.baseline->values;
  const std::size_t tuple = i / static_cast<std::size_t>(values.components);
  std::ostringstream text;
  switch (report.association)
  {
    case Association::Points:
    case Association::PointData:
    {
      text << "point " << tuple;
      const FileArray* points = find(baseline, "points", Association::Points);
      if (points && (tuple + 1) * 3 <= points->values.reals.size())
      {
        const double* p = &points->values.reals[3 * tuple];
        text << " (" << brief(p[0]) << ", " << brief(p[1]) << ", " << brief(p[2]) << ")";
      }
      break;
    }
    case Association::CellData: text << "cell " << tuple; break;
    case Association::FieldData: text << "tuple " << tuple; break;
  }
  if (values.components > 1)
  {
    text << ", component " << i % static_cast<std::size_t>(values.components);
  }
  return text.str();
}

/// The bits of ShadeLab's flags, by their meanings; other bits by number.
std::string bitName(int bit, bool flags)
{
  for (const FlagMeaning& meaning : flagMeanings)
  {
    if (flags && bit < 8 && meaning.flag == (1u << bit))
    {
      return std::to_string(1u << bit) + " (" + meaning.meaning + ")";
    }
  }
  return "bit " + std::to_string(bit);
}

/// The table's columns: widths, and the heading.
constexpr int nameWidth = 30, dataWidth = 7, typeWidth = 11, failingWidth = 18, numberWidth = 11;

void printHeading()
{
  std::cout << "  " << std::left << std::setw(7) << "" << std::setw(nameWidth) << "array"
            << " " << std::setw(dataWidth) << "data" << std::setw(typeWidth) << "type" << std::setw(failingWidth)
            << "failing / values" << std::setw(numberWidth) << "max |diff|" << std::setw(numberWidth) << "RMS"
            << std::setw(numberWidth) << "L2"
            << "rule" << std::right << "\n";
}

/// The array's row of the table, then what a person needs to see about its differences.
/// What a person needs to see about an array's differences beyond its row: the worst value,
/// NaNs, the bits, the standard errors. One line each.
std::vector<std::string> detailsOf(
  const ArrayReport& report, const std::vector<FileArray>& baseline, const std::vector<FileArray>& result)
{
  std::vector<std::string> lines;
  if (!report.difference)
  {
    return lines;
  }
  const ArrayDifference& d = *report.difference;
  if (d.worst && d.largest > 0)
  {
    const FileArray* other = find(result, report.name, report.association);
    lines.push_back(std::string(d.failing > 0 ? "worst failing" : "largest difference") + " at " +
      placeOf(report, *d.worst, baseline) + ": " + valueText(report.baseline->values, *d.worst) + " in the baseline, " +
      valueText(other->values, *d.worst) + " in the result");
  }
  if (d.nanInBoth + d.nanInOne > 0)
  {
    lines.push_back("NaN in both files at " + std::to_string(d.nanInBoth) + " values (equal), in one only at " +
      std::to_string(d.nanInOne) + " (they fail)");
  }
  if (report.baseline->values.type == ValueType::Integer && d.failing > 0)
  {
    std::string text = "bits that differ:";
    const char* separator = " ";
    for (int bit = 0; bit < 64; ++bit)
    {
      if (d.bitCounts[static_cast<std::size_t>(bit)] > 0)
      {
        text +=
          separator + bitName(bit, report.flags) + " in " + std::to_string(d.bitCounts[static_cast<std::size_t>(bit)]);
        separator = ", ";
      }
    }
    lines.push_back(text);
  }
  for (std::size_t component = 0; component < d.noise.size(); ++component)
  {
    lines.push_back(noiseLine(report, component));
  }
  if (!d.noise.empty())
  {
    const int components = report.baseline->values.components;
    lines.push_back("each check at significance " + brief(significancePerCheck(report.rule.significance, components)) +
      " (" + brief(report.rule.significance) + " shared equally by the count and the mean difference" +
      (components > 1 ? " of " + std::to_string(components) + " components" : std::string()) + ", Bonferroni)");
  }
  if (d.exactValues > 0)
  {
    lines.push_back(std::to_string(d.exactValues) + (d.exactValues == 1 ? " value has" : " values have") +
      " both standard errors 0: judged by " + toleranceText(report));
  }
  if (report.rule.standardErrors && d.withStandardError > 0)
  {
    const double n = static_cast<double>(d.withStandardError);
    std::ostringstream text;
    text << "within 1, 2, 3 combined standard errors: " << std::fixed << std::setprecision(1)
         << 100 * d.withinStandardErrors[0] / n << "%, " << 100 * d.withinStandardErrors[1] / n << "%, "
         << 100 * d.withinStandardErrors[2] / n << "% of " << d.withStandardError
         << " values (a normal error: 68.3%, 95.4%, 99.7%)";
    lines.push_back(text.str());
  }
  return lines;
}

/// The verdict in a few words: the reason it could not be compared, or the count that fails.
std::string verdictOf(const ArrayReport& report)
{
  if (!report.problem.empty())
  {
    return report.problem;
  }
  const ArrayDifference& d = *report.difference;
  std::string verdict = std::to_string(d.failing) + " of " + std::to_string(d.values) + " values fail (" +
    ruleText(report) + "); max |diff| " + brief(d.largest);
  for (std::size_t component = 0; component < d.noise.size(); ++component)
  {
    if (!d.noise[component].passes())
    {
      verdict += "; " + noiseLine(report, component);
    }
  }
  return verdict;
}

/// The array's row of the table, then its details.
void printReport(
  const ArrayReport& report, const std::vector<FileArray>& baseline, const std::vector<FileArray>& result)
{
  std::string type;
  if (report.baseline)
  {
    type =
      std::string(typeName(report.baseline->values.type)) + " x" + std::to_string(report.baseline->values.components);
  }
  std::cout << "  " << std::left << std::setw(7) << (report.passes() ? "ok" : "DIFFER") << std::setw(nameWidth)
            << report.name << " " << std::setw(dataWidth) << associationName(report.association) << std::setw(typeWidth)
            << type;
  if (!report.problem.empty())
  {
    std::cout << report.problem << std::right << "\n";
    return;
  }
  const ArrayDifference& d = *report.difference;
  std::cout << std::setw(failingWidth) << (std::to_string(d.failing) + " / " + std::to_string(d.values))
            << std::setw(numberWidth) << brief(d.largest) << std::setw(numberWidth) << brief(d.rms())
            << std::setw(numberWidth) << brief(d.l2()) << ruleText(report) << std::right << "\n";
  for (const std::string& line : detailsOf(report, baseline, result))
  {
    std::cout << "         " << line << "\n";
  }
}

/// The length of the UTF-8 sequence at text[i] if it is a character XML 1.0 may hold
/// (shortest form, no surrogate, not U+FFFE or U+FFFF), else 0.
std::size_t xmlCharacterLength(const std::string& text, std::size_t i)
{
  const auto byte = [&](std::size_t k) { return k < text.size() ? static_cast<unsigned char>(text[k]) : 0u; };
  const unsigned lead = byte(i);
  const std::size_t length = lead < 0x80 ? 1
    : lead >= 0xC2 && lead <= 0xDF       ? 2
    : lead >= 0xE0 && lead <= 0xEF       ? 3
    : lead >= 0xF0 && lead <= 0xF4       ? 4
                                         : 0;
  if (length == 0)
  {
    return 0;
  }
  unsigned code = length == 1 ? lead : lead & (0x7Fu >> length);
  for (std::size_t k = 1; k < length; ++k)
  {
    if ((byte(i + k) & 0xC0u) != 0x80u)
    {
      return 0;
    }
    code = (code << 6) | (byte(i + k) & 0x3Fu);
  }
  const unsigned smallest[] = { 0, 0, 0x80, 0x800, 0x10000 };
  const bool allowed = (code >= 0x20 || code == '\t' || code == '\n' || code == '\r') && code >= smallest[length] &&
    !(code >= 0xD800 && code <= 0xDFFF) && code != 0xFFFE && code != 0xFFFF && code <= 0x10FFFF;
  return allowed ? length : 0;
}

/// Text in XML: the five characters XML reserves escaped, and each byte that is not part of a
/// character XML may hold (a name that is not UTF-8, a control character) as '?'.
std::string xmlText(const std::string& text)
{
  std::string escaped;
  for (std::size_t i = 0; i < text.size();)
  {
    const std::size_t length = xmlCharacterLength(text, i);
    if (length == 0)
    {
      escaped += '?';
      ++i;
      continue;
    }
    const char c = text[i];
    switch (c)
    {
      case '&': escaped += "&amp;"; break;
      case '<': escaped += "&lt;"; break;
      case '>': escaped += "&gt;"; break;
      case '"': escaped += "&quot;"; break;
      case '\'': escaped += "&apos;"; break;
      default: escaped.append(text, i, length);
    }
    i += length;
  }
  return escaped;
}

/// The report as JUnit XML, one test case per array, so that CI systems show each.
std::string junitOf(const std::vector<ArrayReport>& reports, const CompareOptions& options,
  const std::vector<FileArray>& baseline, const std::vector<FileArray>& result)
{
  const std::size_t failures = static_cast<std::size_t>(
    std::count_if(reports.begin(), reports.end(), [](const ArrayReport& r) { return !r.passes(); }));
  std::ostringstream xml;
  xml << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<testsuites name=\"shadelab compare\" tests=\"" << reports.size() << "\" failures=\"" << failures << "\">\n"
      << "  <testsuite name=\"" << xmlText(options.result + " against " + options.baseline) << "\" tests=\""
      << reports.size() << "\" failures=\"" << failures << "\">\n";
  for (const ArrayReport& report : reports)
  {
    xml << "    <testcase classname=\"shadelab.compare." << associationName(report.association) << "\" name=\""
        << xmlText(report.name) << "\"";
    const bool noise = report.difference && !report.difference->noise.empty();
    if (report.passes() && !noise)
    {
      xml << "/>\n";
      continue;
    }
    // A passing noise check says its counts too, as standard output.
    const char* element = report.passes() ? "system-out" : "failure";
    xml << ">\n      <" << element;
    if (!report.passes())
    {
      xml << " message=\"" << xmlText(verdictOf(report)) << "\"";
    }
    xml << ">";
    for (const std::string& line : detailsOf(report, baseline, result))
    {
      xml << xmlText(line) << "\n";
    }
    xml << "</" << element << ">\n    </testcase>\n";
  }
  xml << "  </testsuite>\n</testsuites>\n";
  return xml.str();
}

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
    const FileArray* other = find(result, report.name, report.association);
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

/// How the result's points and cells were matched to the baseline's.
struct Matching
{
  std::string description = "points and cells matched by id";
  /// With --nearest: the baseline's tuple for each of the result's, once moved to it.
  std::vector<vtkIdType> points, cells;
  /// Why the points (or cells) found no match: their arrays are then not compared.
  std::string pointProblem, cellProblem;

  /// The baseline's tuple that the result's tuple moved to.
  std::size_t baselineOf(bool onCells, std::size_t tuple) const
  {
    const std::vector<vtkIdType>& moved = onCells ? cells : points;
    return moved.empty() ? tuple : static_cast<std::size_t>(moved[tuple]);
  }
};

/// For each point of `from`, the nearest point of `to` not yet matched (points with the same
/// coordinates, copies at a seam, match one to one in the order of their ids), within
/// tolerance: a greedy search among each point's 16 nearest. Empty, with the reason in
/// problem, where a point finds none; what says what the points are.
std::vector<vtkIdType> nearestMatches(
  vtkDataSet* from, vtkDataSet* to, double tolerance, const std::string& what, double& farthest, std::string& problem)
{
  vtkNew<vtkStaticPointLocator> locator;
  locator->SetDataSet(to);
  locator->BuildLocator();
  std::vector<vtkIdType> matches(static_cast<std::size_t>(from->GetNumberOfPoints()));
  std::vector<bool> taken(static_cast<std::size_t>(to->GetNumberOfPoints()), false);
  farthest = 0;
  for (vtkIdType i = 0; i < from->GetNumberOfPoints(); ++i)
  {
    double p[3], q[3];
    from->GetPoint(i, p);
    // The nearest few, nearest first and equal distances by id: the first not yet matched.
    constexpr int candidates = 16;
    vtkNew<vtkIdList> near;
    locator->FindClosestNPoints(candidates, p, near);
    std::vector<std::pair<double, vtkIdType>> byDistance;
    for (vtkIdType k = 0; k < near->GetNumberOfIds(); ++k)
    {
      to->GetPoint(near->GetId(k), q);
      byDistance.emplace_back(std::sqrt(vtkMath::Distance2BetweenPoints(p, q)), near->GetId(k));
    }
    std::sort(byDistance.begin(), byDistance.end());
    vtkIdType chosen = -1;
    double distance = byDistance.empty() ? std::numeric_limits<double>::infinity() : byDistance.front().first;
    for (const auto& [d, id] : byDistance)
    {
      if (!taken[static_cast<std::size_t>(id)] && d <= tolerance)
      {
        chosen = id;
        distance = d;
        break;
      }
    }
    if (chosen < 0)
    {
      const bool allTaken = distance <= tolerance;
      problem = "the result's " + what + " " + std::to_string(i) + " (" + brief(p[0]) + ", " + brief(p[1]) + ", " +
        brief(p[2]) + ") has no match in the baseline within " + brief(tolerance) +
        (allTaken ? ": its " + std::to_string(candidates) + " nearest are matched to others"
                  : " (the nearest is " + brief(distance) + " away)");
      return {};
    }
    taken[static_cast<std::size_t>(chosen)] = true;
    matches[static_cast<std::size_t>(i)] = chosen;
    farthest = std::max(farthest, distance);
  }
  return matches;
}

/// The values moved so that tuple i of the result lands where its match, matches[i], is.
void moveTuples(ArrayValues& values, const std::vector<vtkIdType>& matches)
{
  const std::size_t components = static_cast<std::size_t>(values.components);
  auto move = [&](auto& v)
  {
    auto moved = v;
    for (std::size_t i = 0; i < matches.size() && (i + 1) * components <= v.size(); ++i)
    {
      std::copy_n(&v[i * components], components, &moved[static_cast<std::size_t>(matches[i]) * components]);
    }
    v = std::move(moved);
  };
  values.type == ValueType::Integer ? move(values.integers) : move(values.reals);
}

/// The cells' centres, as points (none for a cell without points).
vtkSmartPointer<vtkDataSet> cellCentres(vtkDataSet* data)
{
  vtkNew<vtkCellCenters> centres;
  centres->SetInputData(data);
  centres->VertexCellsOff();
  centres->Update();
  return centres->GetOutput();
}

/// The result's point and cell arrays put in the baseline's order, matching points (and cells,
/// by their centres) by nearest point within the tolerance.
Matching matchByNearest(vtkDataSet* baseline, vtkDataSet* result, std::vector<FileArray>& arrays, double tolerance)
{
  Matching matching;
  std::ostringstream done;
  for (const bool cells : { false, true })
  {
    vtkSmartPointer<vtkDataSet> from = cells ? cellCentres(result) : vtkSmartPointer<vtkDataSet>(result);
    vtkSmartPointer<vtkDataSet> to = cells ? cellCentres(baseline) : vtkSmartPointer<vtkDataSet>(baseline);
    std::string& problem = cells ? matching.cellProblem : matching.pointProblem;
    if (cells &&
      (from->GetNumberOfPoints() != result->GetNumberOfCells() ||
        to->GetNumberOfPoints() != baseline->GetNumberOfCells()))
    {
      problem = "cells without points have no centre, so the cells cannot be matched by their centres";
      continue;
    }
    if (from->GetNumberOfPoints() != to->GetNumberOfPoints() || from->GetNumberOfPoints() == 0)
    {
      continue; // the arrays' counts differ, which their rows will say
    }
    double farthest = 0;
    std::vector<vtkIdType> matches =
      nearestMatches(from, to, tolerance, cells ? "cell centre" : "point", farthest, problem);
    if (!problem.empty())
    {
      continue;
    }
    for (FileArray& array : arrays)
    {
      const bool onCells = array.association == Association::CellData;
      if (array.association != Association::FieldData && onCells == cells)
      {
        moveTuples(array.values, matches);
      }
    }
    done << (cells ? "; cells by their centres, " : "points matched by nearest point, ") << "the farthest "
         << brief(farthest) << " away";
    (cells ? matching.cells : matching.points) = std::move(matches);
  }
  matching.description = done.str().empty() ? "no points or cells matched by nearest point" : done.str();
  return matching;
}

/// What the two files hold: their datasets, their number arrays and those that are not numbers,
/// and how the result's points and cells were matched to the baseline's.
struct ComparedFiles
{
  vtkSmartPointer<vtkDataSet> baselineData, resultData;
  std::vector<FileArray> baseline, result;
  std::vector<SkippedArray> skippedBaseline, skippedResult;
  Matching matching;
};

std::string jsonReport(
  const std::vector<ArrayReport>& reports, bool passed, const ComparedFiles& files, const CompareOptions& options)
{
  nlohmann::json report = { { "baseline", options.baseline }, { "result", options.result }, { "passed", passed },
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

/// The name of the pass/fail arrays of the difference mesh, in its point and cell data.
constexpr const char* passedArrayName = "compare_passed";

/// The result's mesh, with, for each array compared value by value, NAME_difference (result
/// less baseline: float64, or 64-bit integers) beside it, and compare_passed in its point and
/// cell data: 1 where every compared value of the point (or cell) passes, 0 where one fails.
/// Values compared in the baseline's order (--nearest) go back to the result's points. Throws
/// UserError for a result that is not polydata.
vtkSmartPointer<vtkPolyData> differenceMesh(vtkDataSet* resultData, const std::vector<ArrayReport>& reports,
  const std::vector<FileArray>& result, const Matching& matching)
{
  auto* resultMesh = vtkPolyData::SafeDownCast(resultData);
  if (!resultMesh)
  {
    throw UserError(std::string("--diff writes a mesh (.vtp or .vtk), and the result is a ") +
      resultData->GetClassName() + ": leave --diff out for it");
  }
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->ShallowCopy(resultMesh);
  auto passedArray = [](vtkIdType count)
  {
    auto passed = vtkSmartPointer<vtkUnsignedCharArray>::New();
    passed->SetName(passedArrayName);
    passed->SetNumberOfTuples(count);
    passed->FillValue(1);
    return passed;
  };
  vtkSmartPointer<vtkUnsignedCharArray> pointsPassed = passedArray(mesh->GetNumberOfPoints());
  vtkSmartPointer<vtkUnsignedCharArray> cellsPassed = passedArray(mesh->GetNumberOfCells());
  for (const ArrayReport& report : reports)
  {
    if (!report.difference || report.association == Association::FieldData)
    {
      continue;
    }
    const ArrayValues& a = report.baseline->values;
    const ArrayValues& b = find(result, report.name, report.association)->values;
    const bool onCells = report.association == Association::CellData;
    const std::size_t components = static_cast<std::size_t>(a.components);
    // Value c of the result's tuple t: its match's, in the baseline's order.
    auto valueIndex = [&](std::size_t t, std::size_t c) { return matching.baselineOf(onCells, t) * components + c; };
    vtkSmartPointer<vtkDataArray> difference;
    if (a.type == ValueType::Integer)
    {
      auto integers = vtkSmartPointer<vtkTypeInt64Array>::New();
      difference = integers;
      integers->SetNumberOfComponents(a.components);
      integers->SetNumberOfTuples(static_cast<vtkIdType>(a.tuples()));
      for (std::size_t t = 0; t < a.tuples(); ++t)
      {
        for (std::size_t c = 0; c < components; ++c)
        {
          // Wrapping, as a difference of 64-bit values may not fit in 64 bits.
          const std::size_t i = valueIndex(t, c);
          integers->SetValue(static_cast<vtkIdType>(t * components + c),
            static_cast<std::int64_t>(
              static_cast<std::uint64_t>(b.integers[i]) - static_cast<std::uint64_t>(a.integers[i])));
        }
      }
    }
    else
    {
      auto reals = vtkSmartPointer<vtkDoubleArray>::New();
      difference = reals;
      reals->SetNumberOfComponents(a.components);
      reals->SetNumberOfTuples(static_cast<vtkIdType>(a.tuples()));
      for (std::size_t t = 0; t < a.tuples(); ++t)
      {
        for (std::size_t c = 0; c < components; ++c)
        {
          const std::size_t i = valueIndex(t, c);
          reals->SetValue(static_cast<vtkIdType>(t * components + c), b.reals[i] - a.reals[i]);
        }
      }
    }
    difference->SetName((report.name + "_difference").c_str());
    (onCells ? static_cast<vtkFieldData*>(mesh->GetCellData()) : mesh->GetPointData())->AddArray(difference);
    vtkUnsignedCharArray* passed = onCells ? cellsPassed : pointsPassed;
    const std::vector<unsigned char>& tuplePasses = report.difference->tuplePasses;
    for (std::size_t t = 0; t < tuplePasses.size() && t < static_cast<std::size_t>(passed->GetNumberOfValues()); ++t)
    {
      passed->SetValue(static_cast<vtkIdType>(t),
        passed->GetValue(static_cast<vtkIdType>(t)) & tuplePasses[matching.baselineOf(onCells, t)]);
    }
  }
  mesh->GetPointData()->AddArray(pointsPassed);
  mesh->GetCellData()->AddArray(cellsPassed);
  return mesh;
}

std::string datasetText(vtkDataSet* data)
{
  return std::to_string(data->GetNumberOfPoints()) + " points, " + std::to_string(data->GetNumberOfCells()) + " cells";
}

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

bool isSelected(const CompareOptions& options, const std::string& name)
{
  return matchesAny(options.arrays, name) && !matchesAny(options.exclude, name);
}

/// Both files read, their arrays listed (those --arrays and --exclude leave out dropped from
/// the not-numbers lists) and, with --nearest, their points matched.
ComparedFiles readFiles(const CompareOptions& options, RunWarnings& warnings)
{
  ComparedFiles files;
  files.baselineData = readDataSet(options.baseline);
  warnings.collect(options.baseline);
  files.resultData = readDataSet(options.result);
  warnings.collect(options.result);
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

/// Why arrays of this association cannot be compared: their points or cells found no match.
const std::string& matchingProblem(const Matching& matching, Association association)
{
  static const std::string none;
  return association == Association::CellData ? matching.cellProblem
    : association == Association::FieldData   ? none
                                              : matching.pointProblem;
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
  if (!matchingProblem(files.matching, array.association).empty())
  {
    return "not compared: " + matchingProblem(files.matching, array.association);
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
  const FileArray* other = find(files.result, array.name, array.association);
  report.problem = pairingProblem(array, other, files, options);
  if (!report.problem.empty())
  {
    return report;
  }
  const ArrayValues& a = array.values;
  report.rule = rules.ruleFor(array);
  const FileArray* errorsA = find(files.baseline, array.name + "_std_error", array.association);
  const FileArray* errorsB = find(files.result, array.name + "_std_error", array.association);
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
    if (selected(array) && !find(files.baseline, array.name, array.association))
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

/// The console report: what was compared, a line per array, the arrays that are not numbers
/// and the verdict. True when every array passes.
bool printReports(const std::vector<ArrayReport>& reports, const ComparedFiles& files, const CompareOptions& options)
{
  const std::size_t differing = static_cast<std::size_t>(
    std::count_if(reports.begin(), reports.end(), [](const ArrayReport& r) { return !r.passes(); }));
  std::cout << "shadelab compare: the result " << options.result << " (" << datasetText(files.resultData)
            << ") against the baseline " << options.baseline << " (" << datasetText(files.baselineData) << "); "
            << files.matching.description << "\n";
  printHeading();
  for (const ArrayReport& report : reports)
  {
    printReport(report, files.baseline, files.result);
  }
  for (const auto& [file, skipped] :
    { std::pair{ "the baseline", &files.skippedBaseline }, std::pair{ "the result", &files.skippedResult } })
  {
    if (!skipped->empty())
    {
      std::cout << "  not compared in " << file << " (not numbers):";
      for (std::size_t k = 0; k < skipped->size(); ++k)
      {
        std::cout << (k == 0 ? " " : ", ") << (*skipped)[k].description;
      }
      std::cout << "\n";
    }
  }
  if (differing == 0)
  {
    std::cout << "PASS: " << reports.size() << (reports.size() == 1 ? " array agrees" : " arrays agree") << "\n";
  }
  else
  {
    std::cout << "FAIL: " << differing << " of " << reports.size() << " arrays differ\n";
  }
  return differing == 0;
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
    writeTextFile(options.junit, junitOf(reports, options, files.baseline, files.result));
  }
  if (!options.diff.empty())
  {
    writeMesh(differenceMesh(files.resultData, reports, files.result, files.matching), options.diff, Compression::LZ4);
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
      "the file to compare against (.vtp, .vtu, .vti, .vts, .vtr, .vtk, .ply, .obj, .stl)")
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
