#ifndef ShadeLabThreadCount_h
#define ShadeLabThreadCount_h
// A filter's NumberOfThreads: vtkSMPTools' count is one setting for the whole process, so a
// filter that asks for its own runs within vtkSMPTools::LocalScope, and VTK's count is as
// before afterwards.
#include "vtkSMPTools.h"

namespace shadelab
{
/// body() run with at most `threads` threads in vtkSMPTools' loops (0: as VTK is set); what
/// it returns.
template<typename Body>
int runWithThreads(int threads, Body&& body)
{
  if (threads <= 0)
  {
    return body();
  }
  const int before = vtkSMPTools::GetEstimatedNumberOfThreads();
  int result = 0;
  vtkSMPTools::LocalScope(vtkSMPTools::Config{ threads }, [&] { result = body(); });
  // VTK 9.1's LocalScope gives back the setting it found, but where that is 0 (VTK's default)
  // its TBB backend keeps the scope's count: then the count is given back too.
  if (vtkSMPTools::GetEstimatedNumberOfThreads() != before)
  {
    vtkSMPTools::Initialize(before);
  }
  return result;
}
}

#endif
