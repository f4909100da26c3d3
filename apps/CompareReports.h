#pragma once
// shadelab compare's reports of the arrays' verdicts: the table on the console
// (CompareTextReport.cxx), JSON (CompareJsonReport.cxx), JUnit XML (CompareJunitReport.cxx) and
// the difference mesh (CompareDifferenceMesh.cxx), and the lines they share.
#include "CompareCommand.h"
#include "ComparedArrays.h"

#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <cstddef>
#include <string>
#include <vector>

namespace shadelab::app::compare
{
/// The console report: what was compared, a line per array, the arrays that are not numbers
/// and the verdict. True when every array passes.
bool printReports(const std::vector<ArrayReport>& reports, const ComparedFiles& files, const CompareOptions& options);

/// The report as JSON: the files, the verdict, each array's (its rule, its differences and
/// where the worst is), and the arrays that are not numbers.
std::string jsonReport(
  const std::vector<ArrayReport>& reports, bool passed, const ComparedFiles& files, const CompareOptions& options);

/// The report as JUnit XML, one test case per array, so that CI systems show each.
std::string junitReport(
  const std::vector<ArrayReport>& reports, const ComparedFiles& files, const CompareOptions& options);

/// The result's mesh, with, for each array compared value by value, NAME_difference (result
/// less baseline: float64, or 64-bit integers) beside it, and compare_passed in its point and
/// cell data: 1 where every compared value of the point (or cell) passes, 0 where one fails.
/// Values compared in the baseline's order (--nearest) go back to the result's points.
/// resultMesh is the result's dataset, which --diff requires to be a mesh.
vtkSmartPointer<vtkPolyData> differenceMesh(
  vtkPolyData* resultMesh, const std::vector<ArrayReport>& reports, const ComparedFiles& files);

/// Where value i of the array is: "point 12 (x, y, z), component 1".
std::string placeOf(const ArrayReport& report, std::size_t i, const std::vector<FileArray>& baseline);

/// The bits of ShadeLab's flags, by their meanings; other bits by number.
std::string bitName(int bit, bool flags);

/// What a person needs to see about an array's differences beyond its row: the worst value,
/// NaNs, the bits, the standard errors. One line each.
std::vector<std::string> detailsOf(
  const ArrayReport& report, const std::vector<FileArray>& baseline, const std::vector<FileArray>& result);

/// The verdict in a few words: the reason it could not be compared, or the count that fails.
std::string verdictOf(const ArrayReport& report);
}
