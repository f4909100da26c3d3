#pragma once
// Work on untrusted input in a child process, so that whatever the input does to the code
// that reads it (VTK's readers are not hardened: a corrupt PLY file crashes them, loops for
// minutes or asks for gigabytes) becomes a clean error in the parent. The child gets bounded
// processor time and memory, writes no files, and what it prints goes nowhere; it hands its
// result back through a pipe.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace shadelab::app
{
/// What the child may use.
struct IsolationLimits
{
  double cpuSeconds = 60;                 // processor time, after which the child is stopped
  std::size_t memoryBytes = std::size_t(1) << 30; // address space beyond what the process has
};

/// The child's side: what it sends back.
class ChildChannel
{
public:
  explicit ChildChannel(int fd)
    : fd_(fd)
  {
  }
  void warning(const std::string& text) { send('W', text); }
  void result(const std::string& bytes) { send('R', bytes); }
  void failure(const std::string& message) { send('E', message); }

private:
  void send(char kind, const std::string& bytes);
  int fd_;
};

/// How the child's work ended.
struct IsolatedOutcome
{
  enum class End
  {
    Finished,    // it sent a result
    Failed,      // it threw: error holds what()
    OutOfMemory, // it needed more than IsolationLimits::memoryBytes
    TimedOut,    // it used more than IsolationLimits::cpuSeconds
    Crashed,     // a signal ended it: signalName says which
  };
  End end = End::Failed;
  std::string result;
  std::string error;
  std::string signalName;
  std::vector<std::string> warnings;
};

/// Runs work(channel) in a forked child under the limits. The work ends by sending a result
/// or by throwing. Progress written to standard error while it runs still reaches a terminal.
IsolatedOutcome runIsolated(const std::function<void(ChildChannel&)>& work, const IsolationLimits& limits);

/// text with every byte that is not printable ASCII shown as '?', cut to at most maxLength
/// characters: for messages that quote a binary file.
std::string printableText(const std::string& text, std::size_t maxLength = 200);
}
