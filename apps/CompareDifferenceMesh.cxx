#include "CompareReports.h"

#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkPointData.h"
#include "vtkTypeInt64Array.h"
#include "vtkUnsignedCharArray.h"

#include <cstdint>

namespace shadelab::app::compare
{
namespace
{
/// The name of the pass/fail arrays of the difference mesh, in its point and cell data.
constexpr const char* passedArrayName = "compare_passed";

/// compare_passed for count points or cells, each 1 until one of its values fails.
vtkSmartPointer<vtkUnsignedCharArray> passedArray(vtkIdType count)
{
  auto passed = vtkSmartPointer<vtkUnsignedCharArray>::New();
  passed->SetName(passedArrayName);
  passed->SetNumberOfTuples(count);
  passed->FillValue(1);
  return passed;
}

/// NAME_difference for the report's array, at each of the result's tuples: result less
/// baseline, float64, or 64-bit integers.
vtkSmartPointer<vtkDataArray> differenceArray(const ArrayReport& report, const ArrayValues& b, const Matching& matching)
{
  const ArrayValues& a = report.baseline->values;
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
  return difference;
}
}

vtkSmartPointer<vtkPolyData> differenceMesh(
  vtkPolyData* resultMesh, const std::vector<ArrayReport>& reports, const ComparedFiles& files)
{
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->ShallowCopy(resultMesh);
  vtkSmartPointer<vtkUnsignedCharArray> pointsPassed = passedArray(mesh->GetNumberOfPoints());
  vtkSmartPointer<vtkUnsignedCharArray> cellsPassed = passedArray(mesh->GetNumberOfCells());
  for (const ArrayReport& report : reports)
  {
    if (!report.difference || report.association == Association::FieldData)
    {
      continue;
    }
    const ArrayValues& b = findArray(files.result, report.name, report.association)->values;
    const bool onCells = report.association == Association::CellData;
    (onCells ? static_cast<vtkFieldData*>(mesh->GetCellData()) : mesh->GetPointData())
      ->AddArray(differenceArray(report, b, files.matching));
    vtkUnsignedCharArray* passed = onCells ? cellsPassed : pointsPassed;
    const std::vector<unsigned char>& tuplePasses = report.difference->tuplePasses;
    for (std::size_t t = 0; t < tuplePasses.size() && t < static_cast<std::size_t>(passed->GetNumberOfValues()); ++t)
    {
      passed->SetValue(static_cast<vtkIdType>(t),
        passed->GetValue(static_cast<vtkIdType>(t)) & tuplePasses[files.matching.baselineOf(onCells, t)]);
    }
  }
  mesh->GetPointData()->AddArray(pointsPassed);
  mesh->GetCellData()->AddArray(cellsPassed);
  return mesh;
}
}
