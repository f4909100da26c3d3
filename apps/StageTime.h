#pragma once
// How long a stage of a command took, for the commands' "time:" lines.
#include <chrono>

namespace shadelab::app
{
using Clock = std::chrono::steady_clock;

inline double secondsSince(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}
}
