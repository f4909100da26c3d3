#pragma once
// Turns VTK's error output into one clean line for the user. VTK formats an error as
// "ERROR: In <file>, line <n>\n<Class> (<address>): <message>\n\n"; a user wants <message>.
#include "vtkCommand.h"
#include "vtkObject.h"
#include "vtkOutputWindow.h"
#include "vtkSmartPointer.h"

#include <string>

namespace shadelab::app
{
/// Observes ErrorEvent on the objects it watches and keeps the first message's text. While an
/// object has this observer, VTK does not print its errors itself.
class VtkErrorCapture : public vtkCommand
{
public:
  static VtkErrorCapture* New() { return new VtkErrorCapture; }

  void watch(vtkObject* object) { object->AddObserver(vtkCommand::ErrorEvent, this); }

  void Execute(vtkObject*, unsigned long, void* callData) override
  {
    if (message_.empty() && callData)
    {
      message_ = userText(static_cast<const char*>(callData));
    }
  }

  bool failed() const { return !message_.empty(); }
  const std::string& message() const { return message_; }

private:
  static std::string userText(std::string text)
  {
    const std::size_t start = text.find("): ");
    if (start != std::string::npos)
    {
      text = text.substr(start + 3);
    }
    while (!text.empty() && (text.back() == '\n' || text.back() == ' '))
    {
      text.pop_back();
    }
    return text;
  }

  std::string message_;
};

/// Keeps VTK from printing errors of objects nobody watches (the pipeline's own "algorithm
/// returned failure" follow-ups): the watched object's message is the one that explains.
class QuietOutputWindow : public vtkOutputWindow
{
public:
  static QuietOutputWindow* New() { return new QuietOutputWindow; }
  void DisplayText(const char*) override {}
};
}
