#ifndef ShadeLabThreadCount_h
#define ShadeLabThreadCount_h
// A filter's NumberOfThreads: vtkSMPTools' thread count is one setting for the whole process
// (VTK 9.1 has no scoped one), so a filter that asks for its own count sets it while it runs
// and gives back the count it found.
#include "vtkSMPTools.h"

namespace shadelab
{
class ThreadCountWhileRunning
{
public:
  /// threads 0 leaves VTK's setting as it is.
  explicit ThreadCountWhileRunning(int threads)
    : previous_(vtkSMPTools::GetEstimatedNumberOfThreads())
    , changed_(threads > 0 && threads != previous_)
  {
    if (changed_)
    {
      vtkSMPTools::Initialize(threads);
    }
  }
  ~ThreadCountWhileRunning()
  {
    if (changed_)
    {
      vtkSMPTools::Initialize(previous_);
    }
  }
  ThreadCountWhileRunning(const ThreadCountWhileRunning&) = delete;
  ThreadCountWhileRunning& operator=(const ThreadCountWhileRunning&) = delete;

private:
  int previous_;
  bool changed_;
};
}

#endif
