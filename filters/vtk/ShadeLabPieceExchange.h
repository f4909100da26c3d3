#pragma once
// What ShadeLabWholeMesh.cxx and ShadeLabMeshPieces.cxx exchange with: every process's values
// gathered, on every process or on the first only.
#include "ShadeLabMeshPieces.h"
#include "ShadeLabWholeMesh.h"

#include "vtkMultiProcessController.h"

#include <limits>
#include <new>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

namespace shadelab
{
inline int processCount(vtkMultiProcessController* controller)
{
  return controller ? controller->GetNumberOfProcesses() : 1;
}

inline bool isFirstProcess(vtkMultiProcessController* controller)
{
  return !controller || controller->GetLocalProcessId() == 0;
}

/// Whether this process receives what is gathered `where`.
inline bool receives(vtkMultiProcessController* controller, WholeMeshOn where)
{
  return where == WholeMeshOn::EveryProcess || isFirstProcess(controller);
}

/// Every process's `mine`, one after another in process order, on every process or on the
/// first only (the others get nothing); counts[p] is process p's size, on every process.
template<typename T>
std::vector<T> gathered(vtkMultiProcessController* controller, const std::vector<T>& mine, WholeMeshOn where,
  std::vector<vtkIdType>* counts = nullptr)
{
  const int processes = processCount(controller);
  std::vector<vtkIdType> lengths(processes, static_cast<vtkIdType>(mine.size()));
  if (processes == 1)
  {
    if (counts)
    {
      *counts = lengths;
    }
    return mine;
  }
  const vtkIdType length = static_cast<vtkIdType>(mine.size());
  controller->AllGather(&length, lengths.data(), 1);
  std::vector<vtkIdType> offsets(processes, 0);
  std::partial_sum(lengths.begin(), lengths.end() - 1, offsets.begin() + 1);
  const vtkIdType total = offsets.back() + lengths.back();
  // MPI counts are ints: every process finds the same total, and stops alike.
  if (total > std::numeric_limits<int>::max())
  {
    throw std::overflow_error("the mesh is too large to gather: " + std::to_string(total) +
      " values in one exchange, more than MPI's 2^31 - 1");
  }
  if (counts)
  {
    *counts = lengths;
  }
  std::vector<T> all;
  bool allocated = true;
  try
  {
    all.resize(receives(controller, where) ? static_cast<std::size_t>(total) : 0);
  }
  catch (const std::bad_alloc&)
  {
    allocated = false;
  }
  if (!everyProcessHolds(controller, allocated)) // so that every process stops alike
  {
    throw std::runtime_error("out of memory gathering the mesh's pieces (" + std::to_string(total) + " values)");
  }
  const int exchanged = where == WholeMeshOn::EveryProcess
    ? controller->AllGatherV(mine.data(), all.data(), length, lengths.data(), offsets.data())
    : controller->GatherV(mine.data(), all.data(), length, lengths.data(), offsets.data(), 0);
  if (exchanged == 0)
  {
    throw std::runtime_error("gathering the mesh's pieces failed (MPI's gather)");
  }
  return all;
}

template<typename T>
std::vector<T> allGather(
  vtkMultiProcessController* controller, const std::vector<T>& mine, std::vector<vtkIdType>* counts = nullptr)
{
  return gathered(controller, mine, WholeMeshOn::EveryProcess, counts);
}
}
