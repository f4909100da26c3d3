#pragma once
// The tolerance's plan and its cost forecast printed as soon as the filter has chosen them, so
// that a long run says what it will do, and about how long it will take, before it starts.
#include "vtkCommand.h"
#include "vtkLocalReflectanceFilter.h"

#include <cstddef>
#include <iostream>

namespace shadelab::app
{
class PlanBeforeRun : public vtkCommand
{
public:
  static PlanBeforeRun* New() { return new PlanBeforeRun; }

  void watch(vtkLocalReflectanceFilter* filter)
  {
    filter->AddObserver(vtkLocalReflectanceFilter::MethodsChosenEvent, this);
  }

  void Execute(vtkObject* caller, unsigned long, void*) override
  {
    const auto& plan = static_cast<vtkLocalReflectanceFilter*>(caller)->GetMethodPlan();
    if (!plan)
    {
      return;
    }
    const auto lines = plan->describe();
    std::cout << "shadelab shade: methods for the tolerance, chosen before shading:\n";
    for (const auto& line : lines)
    {
      std::cout << "    " << line << "\n";
    }
    std::cout.flush();
    shownLines_ = lines.size();
  }

  /// How many of the plan's lines were printed before the run (they open its describe() after it).
  std::size_t shownLines() const { return shownLines_; }

private:
  std::size_t shownLines_ = 0;
};
}
