#pragma once
// What shadelab compare compares: the two files' arrays with their values copied out, how the
// result's points and cells were matched to the baseline's (CompareMatching.h), and each
// array's verdict, which the reports say (CompareReports.h).
#include "ValueComparison.h"

#include "vtkDataSet.h"
#include "vtkSmartPointer.h"

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace shadelab::app::compare
{
/// Where an array lives in a dataset.
enum class Association
{
  Points,
  PointData,
  CellData,
  FieldData,
};

/// "points", "point", "cell" or "field": where the array is, in the reports' words.
const char* associationName(Association association);

/// An array of one file, its values copied out.
struct FileArray
{
  std::string name;
  Association association = Association::PointData;
  ArrayValues values;
};

/// "float32", "float64" or "integer".
const char* typeName(ValueType type);

/// An array that is not numbers (text, say): its name, and what it is.
struct SkippedArray
{
  std::string name, description;
};

/// The dataset's point coordinates and its numeric arrays; the arrays it holds that are not
/// numbers go to skipped.
std::vector<FileArray> arraysOf(vtkDataSet* data, bool withPoints, std::vector<SkippedArray>& skipped);

/// The array of that name and association, or nullptr.
const FileArray* findArray(const std::vector<FileArray>& arrays, const std::string& name, Association association);

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

  /// Why arrays of this association cannot be compared: their points or cells found no match.
  const std::string& problemOf(Association association) const;
};

/// What the two files hold: their datasets, their number arrays and those that are not numbers,
/// and how the result's points and cells were matched to the baseline's.
struct ComparedFiles
{
  vtkSmartPointer<vtkDataSet> baselineData, resultData;
  /// How each was put in the order compared (ComparedPieces.h): "" where as read.
  std::string baselineOrder, resultOrder;
  std::vector<FileArray> baseline, result;
  std::vector<SkippedArray> skippedBaseline, skippedResult;
  Matching matching;
};

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
std::string brief(double x);
std::string exact(double x);
}
