#pragma once
// A real-valued output array in the precision a run chose.
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkSmartPointer.h"

#include <string>

namespace shadelab
{
/// A named array of `tuples` tuples of `components`, in float64 or float32, its values unset.
inline vtkSmartPointer<vtkDataArray> realArray(const std::string& name, int components, vtkIdType tuples, bool float64)
{
  vtkSmartPointer<vtkDataArray> array = float64 ? vtkSmartPointer<vtkDataArray>(vtkSmartPointer<vtkDoubleArray>::New())
                                                : vtkSmartPointer<vtkDataArray>(vtkSmartPointer<vtkFloatArray>::New());
  array->SetName(name.c_str());
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(tuples);
  return array;
}
}
