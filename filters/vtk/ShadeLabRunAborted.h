#pragma once
// A run that stopped because its pipeline asked it to (vtkAlgorithm::SetAbortExecute, which
// ParaView's Cancel sets): thrown from the long loops between their blocks, caught where the
// filter leaves an empty output and no error.
#include <stdexcept>

namespace shadelab
{
struct RunAborted : std::runtime_error
{
  RunAborted()
    : std::runtime_error("the run was aborted")
  {
  }
};
}
