#include "ComparedArrays.h"

#include "NumberText.h"

#include "vtkArrayDispatch.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDataArrayRange.h"
#include "vtkFieldData.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"

#include <cstdint>
#include <type_traits>
#include <utility>

namespace shadelab::app::compare
{
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

namespace
{
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

}

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

const FileArray* findArray(const std::vector<FileArray>& arrays, const std::string& name, Association association)
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

const std::string& Matching::problemOf(Association association) const
{
  static const std::string none;
  return association == Association::CellData ? cellProblem
    : association == Association::FieldData   ? none
                                              : pointProblem;
}

std::string brief(double x)
{
  return withDigits(x, 3);
}

std::string exact(double x)
{
  return withDigits(x, 17);
}

}
