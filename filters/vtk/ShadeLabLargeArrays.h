#pragma once
// Memory for large output arrays, backed by transparent huge pages where Linux gives them on
// request (/sys/kernel/mm/transparent_hugepage/enabled set to "madvise", Debian's default).
// A newly allocated array is mapped page by page as it is first written: with 4 kB pages a
// 120 MB array costs 30,000 page faults, which on this project's 2-core virtual machine took
// 260 to 480 ms, twenty times the shading itself; with 2 MB pages it costs 60 and took 6 to 11 ms.
#include "ShadeLabFiltersModule.h" // export macro

#include "vtkAOSDataArrayTemplate.h"

#include <cstddef>

namespace shadelab
{
/// `bytes` of uninitialised memory for one array, to be released with std::free; nullptr
/// when there is not enough memory. Blocks of 4 MB or more are aligned to 2 MB and marked
/// for huge pages.
SHADELABFILTERS_EXPORT void* allocateLarge(std::size_t bytes);

/// Gives `array` room for `tuples` tuples (of its number of components) from allocateLarge.
/// Returns false, leaving the array empty, when there is not enough memory.
template <typename T>
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
