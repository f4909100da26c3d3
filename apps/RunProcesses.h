#pragma once
// The processes a run is made of: those `mpiexec -np N` started (N > 1), which shade a mesh
// split among them (docs/guide/mpi.md), or this process alone.
#include <functional>
#include <string>
#include <vector>

class vtkMultiProcessController;

namespace shadelab::app
{
/// While it lives, the processes that mpiexec started are joined through MPI (VTK's
/// vtkMPIController, made VTK's global controller, which the filters take by default). Only the
/// first prints: the others' output and errors go to /dev/null, and what they must say reaches
/// the first through onEveryProcess. In a process that runs alone nothing is done, and MPI is
/// not started.
class RunProcesses
{
public:
  RunProcesses(int* argc, char*** argv);
  ~RunProcesses();
  RunProcesses(const RunProcesses&) = delete;
  RunProcesses& operator=(const RunProcesses&) = delete;
};

/// The run's processes; nullptr where this process runs alone.
vtkMultiProcessController* runProcesses();

/// How many processes the run has, and which this one is (0 to count - 1).
int runProcessCount();
int runProcessIndex();

/// Whether mine holds on some process of the run (a collective call where it has several).
bool onAnyRunProcess(bool mine);

/// Every process's lines, each once, in process order (a collective call).
std::vector<std::string> distinctLinesOfEveryProcess(const std::vector<std::string>& mine);

/// Runs stage on every process (a collective call). Where it throws on any, every process
/// throws UserError with one message: that of the first process that failed on its own (not
/// because another had: ShadeLabMeshPieces.h's saysAnotherProcessFailed), so that the first
/// process says why, and no process waits for another that has stopped.
void onEveryProcess(const std::function<void()>& stage);
}
