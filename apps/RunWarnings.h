#pragma once
// The warnings VTK gives during a run (a reader's complaint about a truncated block, say),
// each naming the file it concerns.
#include "RunProcesses.h"
#include "VtkErrorCapture.h"

#include <iostream>
#include <string>
#include <vector>

namespace shadelab::app
{
/// Collected as the run goes, and shown once it has succeeded: a run that fails ends in its
/// one line, the error.
class RunWarnings
{
public:
  /// Takes the warnings VTK gave since the last call, as being about this file.
  void collect(const std::string& about)
  {
    if (auto* window = QuietOutputWindow::SafeDownCast(vtkOutputWindow::GetInstance()))
    {
      for (const std::string& warning : window->takeWarnings())
      {
        lines_.push_back("shadelab: warning: " + about + ": " + warning);
      }
    }
  }
  /// Every process's warnings, each line once, in process order (a collective call under
  /// mpiexec: each process reads and shades its own piece, and only the first prints).
  void gatherFromEveryProcess() { lines_ = distinctLinesOfEveryProcess(lines_); }
  void show() const
  {
    for (const std::string& line : lines_)
    {
      std::cerr << line << "\n";
    }
  }

private:
  std::vector<std::string> lines_;
};
}
