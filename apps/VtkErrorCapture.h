#pragma once
// Turns VTK's error output into one clean line for the user. VTK formats an error as
// "ERROR: In <file>, line <n>\n<Class> (<address>): <message>\n\n"; a user wants <message>.
#include "vtkCommand.h"
#include "vtkLogger.h"
#include "vtkObject.h"
#include "vtkOutputWindow.h"
#include "vtkSmartPointer.h"

#include <regex>
#include <string>
#include <vector>

namespace shadelab::app
{
/// The text a user wants from a VTK message. VTK formats an object's error or warning as
/// "<Kind>: In <file>, line <n>\n<Class> (<address>): <text>\n\n" and a generic warning as
/// "Generic Warning: In <file>, line <n>\n<text>\n\n".
inline std::string messageText(std::string message)
{
  static const std::regex location("^(ERROR|Warning|Generic Warning): In [^\n]*\n");
  static const std::regex source("^[A-Za-z0-9_]+ \\(0x[0-9a-fA-F]+\\): ");
  message = std::regex_replace(message, location, "", std::regex_constants::format_first_only);
  message = std::regex_replace(message, source, "", std::regex_constants::format_first_only);
  while (!message.empty() && (message.back() == '\n' || message.back() == ' '))
  {
    message.pop_back();
  }
  return message;
}

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
      message_ = messageText(static_cast<const char*>(callData));
    }
  }

  bool failed() const { return !message_.empty(); }
  const std::string& message() const { return message_; }

private:
  std::string message_;
};

/// Keeps VTK from printing errors of objects nobody watches (the pipeline's own "algorithm
/// returned failure" follow-ups): the watched object's message is the one that explains.
/// Warnings are kept, for the command to show as one line each.
class QuietOutputWindow : public vtkOutputWindow
{
public:
  static QuietOutputWindow* New() { return new QuietOutputWindow; }
  vtkTypeMacro(QuietOutputWindow, vtkOutputWindow);
  void DisplayText(const char*) override {}
  void DisplayWarningText(const char* text) override { warnings_.push_back(messageText(text)); }
  void DisplayGenericWarningText(const char* text) override { warnings_.push_back(messageText(text)); }

  /// The warnings since the last call.
  std::vector<std::string> takeWarnings() { return std::move(warnings_); }

private:
  std::vector<std::string> warnings_;
};

/// Errors reach the user as one line each, from the objects ShadeLab watches; VTK's own log
/// would repeat them with source locations and pipeline dumps. (--verbose keeps it.)
inline void quietenVtk()
{
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  vtkOutputWindow::SetInstance(vtkSmartPointer<QuietOutputWindow>::New());
}
}
