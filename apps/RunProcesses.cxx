#include "RunProcesses.h"

#include "MeshFiles.h"

#include "ShadeLabMeshPieces.h"
#include "ShadeLabPieceExchange.h"

#include "vtkMPIController.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <cstdlib>
#include <fcntl.h>
#include <iostream>
#include <new>
#include <sstream>
#include <string>
#include <unistd.h>

namespace shadelab::app
{
namespace
{
vtkSmartPointer<vtkMPIController> joined;

/// How many processes mpiexec started with this one, from what it puts in their environment
/// (Open MPI's, or MPICH's and other PMI launchers'); 1 where it did not start this one.
int processesStarted()
{
  for (const char* variable : { "OMPI_COMM_WORLD_SIZE", "PMI_SIZE" })
  {
    if (const char* value = std::getenv(variable))
    {
      return std::atoi(value);
    }
  }
  return 1;
}

/// Sends this process's standard output and error to /dev/null.
void silence()
{
  const int null = ::open("/dev/null", O_WRONLY);
  if (null >= 0)
  {
    ::dup2(null, STDOUT_FILENO);
    ::dup2(null, STDERR_FILENO);
    ::close(null);
  }
}
}

RunProcesses::RunProcesses(int* argc, char*** argv)
{
  const int started = processesStarted();
  if (started <= 1)
  {
    return;
  }
  joined = vtkSmartPointer<vtkMPIController>::New();
  joined->Initialize(argc, argv);
  if (joined->GetNumberOfProcesses() != started)
  {
    // Each process would take itself for the only one, and all would write the same file.
    std::cerr << "shadelab: mpiexec started " << started << " processes, but MPI joined "
              << joined->GetNumberOfProcesses()
              << ": this mpiexec belongs to another MPI than the one VTK was built with (on Debian, Open MPI's "
                 "/usr/bin/mpiexec)\n";
    joined->Finalize();
    std::exit(1);
  }
  vtkMultiProcessController::SetGlobalController(joined);
  if (joined->GetLocalProcessId() != 0)
  {
    silence();
  }
}

RunProcesses::~RunProcesses()
{
  if (joined)
  {
    vtkMultiProcessController::SetGlobalController(nullptr);
    joined->Finalize();
    joined = nullptr;
  }
}

vtkMultiProcessController* runProcesses()
{
  return joined;
}

int runProcessCount()
{
  return joined ? joined->GetNumberOfProcesses() : 1;
}

int runProcessIndex()
{
  return joined ? joined->GetLocalProcessId() : 0;
}

bool onAnyRunProcess(bool mine)
{
  return !everyProcessHolds(joined, !mine);
}

std::vector<std::string> distinctLinesOfEveryProcess(const std::vector<std::string>& mine)
{
  if (!joined)
  {
    return mine;
  }
  std::string text;
  for (const std::string& line : mine)
  {
    text += line + '\n';
  }
  const std::vector<char> all = allGather(joined.GetPointer(), std::vector<char>(text.begin(), text.end()));
  std::vector<std::string> lines;
  std::istringstream every(std::string(all.begin(), all.end()));
  for (std::string line; std::getline(every, line);)
  {
    if (std::find(lines.begin(), lines.end(), line) == lines.end())
    {
      lines.push_back(line);
    }
  }
  return lines;
}

void onEveryProcess(const std::function<void()>& stage)
{
  if (!joined)
  {
    stage(); // alone: its errors reach the user as they are
    return;
  }
  std::string failure;
  try
  {
    stage();
  }
  catch (const std::bad_alloc&)
  {
    failure = "not enough memory for this run (a smaller mesh, fewer arrays or float32 need less)";
  }
  catch (const std::exception& error)
  {
    failure = error.what();
  }
  const bool ownFailure = !failure.empty() && !saysAnotherProcessFailed(failure);
  std::string agreed = firstText(joined, ownFailure ? failure : "");
  agreed = agreed.empty() ? firstText(joined, failure) : agreed;
  if (!agreed.empty())
  {
    throw UserError(agreed);
  }
}
}
