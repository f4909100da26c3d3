#pragma once
// Large VTK output arrays in huge pages (LargeMemory.h).
#include "LargeMemory.h"

#include "vtkAOSDataArrayTemplate.h"

namespace shadelab
{
/// Gives `array` room for `tuples` tuples (of its number of components) from allocateLarge.
/// Returns false, leaving the array empty, when there is not enough memory.
template<typename T>
bool allocateTuples(vtkAOSDataArrayTemplate<T>* array, vtkIdType tuples)
{
  const vtkIdType values = tuples * array->GetNumberOfComponents();
  void* memory = allocateLarge(static_cast<std::size_t>(values) * sizeof(T));
  if (!memory)
  {
    return false;
  }
  array->SetArray(static_cast<T*>(memory), values, 0, vtkAbstractArray::VTK_DATA_ARRAY_FREE);
  return true;
}
}
