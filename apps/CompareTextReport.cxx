#include "CompareReports.h"

#include "NoiseTest.h"
#include "ShadingFlags.h"

#include "vtkDataSet.h"

#include <algorithm>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <utility>

namespace shadelab::app::compare
{
namespace
{
/// Value i as the reports show it: an integer as it is, any other with all its digits.
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

/// The whole rule of an array: its tolerance, and in statistical mode the noise checks'.
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
}

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
      const FileArray* points = findArray(baseline, "points", Association::Points);
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
    const FileArray* other = findArray(result, report.name, report.association);
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

namespace
{
/// The table's columns' widths.
constexpr int nameWidth = 30, dataWidth = 7, typeWidth = 11, failingWidth = 18, numberWidth = 11;

/// The table's heading.
void printHeading()
{
  std::cout << "  " << std::left << std::setw(7) << "" << std::setw(nameWidth) << "array"
            << " " << std::setw(dataWidth) << "data" << std::setw(typeWidth) << "type" << std::setw(failingWidth)
            << "failing / values" << std::setw(numberWidth) << "max |diff|" << std::setw(numberWidth) << "RMS"
            << std::setw(numberWidth) << "L2"
            << "rule" << std::right << "\n";
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

/// "N points, M cells", and how they were put in the order compared.
std::string datasetText(vtkDataSet* data, const std::string& order)
{
  return std::to_string(data->GetNumberOfPoints()) + " points, " + std::to_string(data->GetNumberOfCells()) + " cells" +
    (order.empty() ? "" : ", " + order);
}
}

bool printReports(const std::vector<ArrayReport>& reports, const ComparedFiles& files, const CompareOptions& options)
{
  const std::size_t differing = static_cast<std::size_t>(
    std::count_if(reports.begin(), reports.end(), [](const ArrayReport& r) { return !r.passes(); }));
  std::cout << "shadelab compare: the result " << options.result << " ("
            << datasetText(files.resultData, files.resultOrder) << ") against the baseline " << options.baseline << " ("
            << datasetText(files.baselineData, files.baselineOrder) << "); " << files.matching.description << "\n";
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
}
