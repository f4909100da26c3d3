#pragma once
// "reading 40%" on one terminal line while VTK works, for runs long enough to wonder about.
// Only on a terminal, so logs and pipes stay clean.
#include "vtkAlgorithm.h"
#include "vtkCommand.h"

#include <cstdio>
#include <string>
#include <unistd.h>

namespace shadelab::app
{
class ProgressLine : public vtkCommand
{
public:
  static ProgressLine* New() { return new ProgressLine; }

  /// A run cut short by an error leaves no half line for the error to follow.
  ~ProgressLine() override
  {
    if (lastPercent_ >= 0 && lastPercent_ < 100)
    {
      clear();
    }
  }

  /// Shows the progress of algorithm under this label, on terminal (by default standard
  /// error, if it is a terminal; null: nowhere).
  void watch(
    vtkAlgorithm* algorithm, const std::string& label, std::FILE* terminal = ::isatty(STDERR_FILENO) ? stderr : nullptr)
  {
    terminal_ = terminal;
    if (terminal_)
    {
      label_ = label;
      lastPercent_ = -1;
      algorithm->AddObserver(vtkCommand::ProgressEvent, this);
    }
  }

  void Execute(vtkObject*, unsigned long, void* callData) override
  {
    const int percent = static_cast<int>(100.0 * *static_cast<double*>(callData));
    if (percent == lastPercent_)
    {
      return;
    }
    lastPercent_ = percent;
    // \r returns to the line's start; at 100% the line is blanked for what follows.
    if (percent >= 100)
    {
      clear();
      return;
    }
    std::fprintf(terminal_, "\r%s %3d%%", label_.c_str(), percent);
    std::fflush(terminal_);
  }

private:
  void clear()
  {
    std::fprintf(terminal_, "\r%*s\r", static_cast<int>(label_.size()) + 6, "");
    std::fflush(terminal_);
  }

  std::string label_;
  std::FILE* terminal_ = nullptr;
  int lastPercent_ = -1;
};
}
