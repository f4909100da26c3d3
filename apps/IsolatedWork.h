#pragma once
// Work on untrusted input in a child process, so that whatever the input does to the code
// that reads it (VTK's readers are not hardened: a corrupt PLY file crashes them, loops for
// minutes or asks for gigabytes) becomes a clean error in the parent. The child gets bounded
// processor time, memory and file output, and what it prints goes nowhere. It hands its
// result back in an anonymous in-memory file (memfd), which the parent reads as a file, so
// that a large result is neither copied through a pipe nor held twice in memory; warnings and
// errors come back through a pipe.
#include <cstddef>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

namespace shadelab::app
{
/// What the child may use.
struct IsolationLimits
{
  double cpuSeconds = 60;                         // processor time, after which the child is stopped
  double wallSeconds = 180;                       // time on the clock, likewise: a child that waits
                                                  // (on a lock, a pipe) uses no processor time
  std::size_t memoryBytes = std::size_t(1) << 30; // address space beyond what the process has,
                                                  // and the largest result file
};

/// The child's side: what it sends back.
class ChildChannel
{
public:
  ChildChannel(int fd, std::string resultPath, std::FILE* terminal)
    : fd_(fd)
    , resultPath_(std::move(resultPath))
    , terminal_(terminal)
  {
  }
  /// The terminal that standard error was, for progress, or null when it was none.
  std::FILE* terminal() const { return terminal_; }
  void warning(const std::string& text) { send('W', text); }
  /// Where to write the result, as a file path (the memfd, seen through /proc).
  const std::string& resultPath() const { return resultPath_; }
  /// The result file is complete.
  void finished() { send('R', ""); }
  void failure(const std::string& message) { send('E', message); }

private:
  void send(char kind, const std::string& bytes);
  int fd_;
  std::string resultPath_;
  std::FILE* terminal_;
};

/// How the child's work ended. Holds the result file open while it lives.
struct IsolatedOutcome
{
  IsolatedOutcome() = default;
  IsolatedOutcome(const IsolatedOutcome&) = delete;
  IsolatedOutcome& operator=(const IsolatedOutcome&) = delete;
  IsolatedOutcome(IsolatedOutcome&& other) noexcept;
  ~IsolatedOutcome();

  enum class End
  {
    Finished,    // it wrote its result: resultPath
    Failed,      // it threw: error holds what()
    OutOfMemory, // it needed more than IsolationLimits::memoryBytes
    TimedOut,    // it used more than IsolationLimits::cpuSeconds
    Stalled,     // it had not ended after IsolationLimits::wallSeconds
    Crashed,     // a signal ended it: signalName says which
    Stopped,     // the parent stopped it: what it checked meanwhile makes the result moot
  };
  End end = End::Failed;
  std::string resultPath; // Finished: the result file, readable while this outcome lives
  std::string error;
  std::string signalName;
  std::vector<std::string> warnings;
  int resultFd = -1;
};

/// Runs work(channel) in a forked child under the limits. The work ends by writing its result
/// to channel.resultPath() and calling channel.finished(), or by throwing. Progress written to standard error while it
/// runs still reaches a terminal. meanwhile, if given, runs in this process while the child works
/// (on another core); when it returns false the child is stopped, and the outcome is Stopped.
IsolatedOutcome runIsolated(const std::function<void(ChildChannel&)>& work, const IsolationLimits& limits,
  const std::function<bool()>& meanwhile = {});

/// text with every byte that is not printable ASCII shown as '?', cut to at most maxLength
/// characters: for messages that quote a binary file.
std::string printableText(const std::string& text, std::size_t maxLength = 200);
}
