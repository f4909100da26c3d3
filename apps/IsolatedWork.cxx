#include "IsolatedWork.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <fstream>
#include <new>
#include <poll.h>
#include <stdexcept>
#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

// Defined by the sanitizer runtimes, absent otherwise (hence weak).
extern "C" void __sanitizer_set_death_callback(void (*callback)(void)) __attribute__((weak));

namespace shadelab::app
{
namespace
{
void writeAll(int fd, const char* data, std::size_t size)
{
  while (size > 0)
  {
    const ssize_t written = ::write(fd, data, size);
    if (written < 0 && errno == EINTR)
    {
      continue;
    }
    if (written <= 0)
    {
      ::_exit(3); // the parent has gone: nothing left to report to
    }
    data += written;
    size -= static_cast<std::size_t>(written);
  }
}

/// Everything written to fd until it is closed, or until the deadline has passed: then
/// stalled is set.
std::string readAll(int fd, std::chrono::steady_clock::time_point deadline, bool& stalled)
{
  std::string bytes;
  char buffer[1 << 16];
  for (;;)
  {
    const auto left =
      std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    pollfd wait{ fd, POLLIN, 0 };
    const int ready =
      left.count() > 0 ? ::poll(&wait, 1, static_cast<int>(std::min<long long>(left.count(), 1 << 30))) : 0;
    if (ready < 0 && errno == EINTR)
    {
      continue;
    }
    if (ready == 0)
    {
      stalled = true;
      return bytes;
    }
    const ssize_t got = ::read(fd, buffer, sizeof buffer);
    if (got < 0 && errno == EINTR)
    {
      continue;
    }
    if (got <= 0)
    {
      return bytes;
    }
    bytes.append(buffer, static_cast<std::size_t>(got));
  }
}

/// The process's address space now, from /proc (0 where it cannot be read).
std::size_t currentAddressSpace()
{
  std::ifstream status("/proc/self/status");
  std::string key;
  while (status >> key)
  {
    if (key == "VmSize:")
    {
      std::size_t kilobytes = 0;
      status >> kilobytes;
      return kilobytes * 1024;
    }
    status.ignore(1 << 12, '\n');
  }
  return 0;
}

/// Waits, for a second at most, until every other thread of this process waits on something.
/// A thread that a library starts as it is loaded (OpenImageIO's dependencies start a logging
/// pool of four) may still be running its start, and hold a lock of the allocator, when this
/// thread forks: the child, which has only a copy of the lock, then waits for it forever.
/// glibc's malloc takes its locks around fork; the allocator of clang 14's AddressSanitizer
/// does not. This makes the hazard rarer, not impossible: a waiting thread may wake between the
/// look and the fork, or wait while it holds a lock.
void waitForOtherThreadsToWait()
{
  const std::string self = std::to_string(::gettid());
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(1);
  while (std::chrono::steady_clock::now() < deadline)
  {
    bool waiting = true;
    std::error_code error;
    for (const auto& task : std::filesystem::directory_iterator("/proc/self/task", error))
    {
      std::ifstream stat(task.path() / "stat");
      std::string line;
      std::getline(stat, line);
      const std::size_t name = line.rfind(')'); // the state follows the name, which may hold spaces
      if (task.path().filename() != self && name != std::string::npos && line.size() > name + 2 &&
        line[name + 2] != 'S')
      {
        waiting = false;
        break;
      }
    }
    if (waiting)
    {
      return;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

/// A child stopped while it showed its progress leaves no half line for what follows.
void clearProgressLine()
{
  if (::isatty(STDERR_FILENO))
  {
    std::fprintf(stderr, "\r%40s\r", "");
    std::fflush(stderr);
  }
}

void limit(int resource, rlim_t value)
{
  const rlimit bound{ value, value };
  ::setrlimit(resource, &bound);
}

[[noreturn]] void runChild(
  int fd, const std::string& resultPath, const std::function<void(ChildChannel&)>& work, const IsolationLimits& limits)
{
  // The child dies of its own faults: handlers the parent installed (a sanitizer's, a
  // fuzzer's) would report them as the parent's and exit instead.
  for (int signal : { SIGSEGV, SIGBUS, SIGABRT, SIGFPE, SIGILL })
  {
    std::signal(signal, SIG_DFL);
  }
  // Likewise a sanitizer's report of a memory error in the work: the callback a fuzzer set
  // would save the input as a crash of the parent's.
  if (__sanitizer_set_death_callback)
  {
    __sanitizer_set_death_callback(nullptr);
  }
  // What the work's libraries print goes nowhere (VTK's PLY code writes to standard error
  // directly, a line per missing element); the terminal, if standard error is one, stays
  // reachable for progress through a descriptor of its own.
  std::FILE* terminal = ::isatty(STDERR_FILENO) ? ::fdopen(::dup(STDERR_FILENO), "w") : nullptr;
  const int devNull = ::open("/dev/null", O_WRONLY);
  ::dup2(devNull, STDOUT_FILENO);
  ::dup2(devNull, STDERR_FILENO);
  const rlim_t seconds = static_cast<rlim_t>(std::ceil(limits.cpuSeconds));
  const rlimit cpu{ seconds, seconds + 1 }; // SIGXCPU at the soft limit, SIGKILL a second later
  ::setrlimit(RLIMIT_CPU, &cpu);
  limit(RLIMIT_AS, static_cast<rlim_t>(currentAddressSpace() + limits.memoryBytes));
  limit(RLIMIT_FSIZE, static_cast<rlim_t>(limits.memoryBytes)); // its result, and no more
  limit(RLIMIT_CORE, 0);
  ChildChannel channel(fd, resultPath, terminal);
  try
  {
    work(channel);
  }
  catch (const std::bad_alloc&)
  {
    ::_exit(4);
  }
  catch (const std::length_error&) // a size too large for a std::vector, asked for by a count
  {
    ::_exit(4);
  }
  catch (const std::exception& error)
  {
    channel.failure(error.what());
  }
  catch (...)
  {
    channel.failure("an unknown error");
  }
  ::_exit(0); // not exit(): the parent's static objects are the parent's to destroy
}

/// Splits the child's records: a kind byte, an 8-byte length, the bytes.
void decode(const std::string& bytes, IsolatedOutcome& outcome)
{
  std::size_t at = 0;
  while (at + 9 <= bytes.size())
  {
    const char kind = bytes[at];
    std::uint64_t length = 0;
    std::memcpy(&length, bytes.data() + at + 1, sizeof length);
    at += 9;
    if (length > bytes.size() - at)
    {
      return; // cut short: the child died while writing
    }
    std::string payload = bytes.substr(at, length);
    at += length;
    if (kind == 'W')
    {
      outcome.warnings.push_back(std::move(payload));
    }
    else if (kind == 'E')
    {
      outcome.end = IsolatedOutcome::End::Failed;
      outcome.error = std::move(payload);
    }
    else if (kind == 'R')
    {
      outcome.end = IsolatedOutcome::End::Finished;
    }
  }
}
}

void ChildChannel::send(char kind, const std::string& bytes)
{
  const std::uint64_t length = bytes.size();
  char header[9];
  header[0] = kind;
  std::memcpy(header + 1, &length, sizeof length);
  writeAll(fd_, header, sizeof header);
  writeAll(fd_, bytes.data(), bytes.size());
}

IsolatedOutcome::IsolatedOutcome(IsolatedOutcome&& other) noexcept
  : end(other.end)
  , resultPath(std::move(other.resultPath))
  , error(std::move(other.error))
  , signalName(std::move(other.signalName))
  , warnings(std::move(other.warnings))
  , resultFd(other.resultFd)
{
  other.resultFd = -1;
}

IsolatedOutcome::~IsolatedOutcome()
{
  if (resultFd >= 0)
  {
    ::close(resultFd);
  }
}

IsolatedOutcome runIsolated(
  const std::function<void(ChildChannel&)>& work, const IsolationLimits& limits, const std::function<bool()>& meanwhile)
{
  IsolatedOutcome outcome;
  outcome.resultFd = ::memfd_create("shadelab-result", 0);
  int channel[2];
  if (outcome.resultFd < 0 || ::pipe(channel) != 0)
  {
    throw std::runtime_error(std::string("cannot start a reader process: ") + std::strerror(errno));
  }
  const std::string resultPath = "/proc/self/fd/" + std::to_string(outcome.resultFd);
  std::fflush(nullptr); // nothing buffered is written twice, once by each process
  waitForOtherThreadsToWait();
  const pid_t child = ::fork();
  if (child < 0)
  {
    ::close(channel[0]);
    ::close(channel[1]);
    throw std::runtime_error(std::string("cannot start a reader process: ") + std::strerror(errno));
  }
  if (child == 0)
  {
    ::close(channel[0]);
    runChild(channel[1], resultPath, work, limits);
  }
  ::close(channel[1]);
  auto stopChild = [&]
  {
    ::close(channel[0]);
    ::kill(child, SIGKILL);
    while (::waitpid(child, nullptr, 0) < 0 && errno == EINTR)
    {
    }
    clearProgressLine();
  };
  try
  {
    if (meanwhile && !meanwhile())
    {
      stopChild();
      outcome.end = IsolatedOutcome::End::Stopped;
      return outcome;
    }
  }
  catch (...)
  {
    stopChild(); // no reader left running after the error
    throw;
  }
  bool stalled = false;
  const auto deadline =
    std::chrono::steady_clock::now() + std::chrono::milliseconds(static_cast<long long>(limits.wallSeconds * 1000));
  const std::string bytes = readAll(channel[0], deadline, stalled);
  ::close(channel[0]);
  if (stalled)
  {
    ::kill(child, SIGKILL);
  }
  int status = 0;
  while (::waitpid(child, &status, 0) < 0 && errno == EINTR)
  {
  }
  decode(bytes, outcome);
  outcome.resultPath = resultPath; // the same descriptor number here as in the child
  if (stalled)
  {
    outcome.end = IsolatedOutcome::End::Stalled;
  }
  else if (WIFSIGNALED(status))
  {
    const int signal = WTERMSIG(status);
    outcome.end =
      signal == SIGXCPU || signal == SIGKILL ? IsolatedOutcome::End::TimedOut : IsolatedOutcome::End::Crashed;
    outcome.signalName = std::string("SIG") + (sigabbrev_np(signal) ? sigabbrev_np(signal) : "?");
  }
  else if (WIFEXITED(status) && WEXITSTATUS(status) == 4)
  {
    outcome.end = IsolatedOutcome::End::OutOfMemory;
  }
  else if (outcome.end == IsolatedOutcome::End::Finished && !(WIFEXITED(status) && WEXITSTATUS(status) == 0))
  {
    outcome.end = IsolatedOutcome::End::Crashed; // it sent a result, then failed: trust neither
    outcome.signalName = "exit code " + std::to_string(WEXITSTATUS(status));
  }
  else if (outcome.end == IsolatedOutcome::End::Failed && outcome.error.empty())
  {
    outcome.end = IsolatedOutcome::End::Crashed;
    outcome.signalName = "exit code " + std::to_string(WEXITSTATUS(status));
  }
  return outcome;
}

std::string printableText(const std::string& text, std::size_t maxLength)
{
  std::string shown;
  for (const char c : text)
  {
    if (shown.size() == maxLength)
    {
      shown += "...";
      break;
    }
    shown += c >= 0x20 && c < 0x7f ? c : '?';
  }
  return shown;
}
}
