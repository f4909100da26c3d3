#pragma once
// Resident memory of this process, from Linux's /proc/self, for the benchmark's "peak memory"
// column: reset the peak, run a case, read the peak.
#include <cstddef>
#include <fstream>
#include <optional>
#include <string>

namespace shadelab::app
{
/// A field of /proc/self/status in bytes (VmRSS: resident now; VmHWM: the peak).
inline std::optional<std::size_t> statusBytes(const std::string& field)
{
  std::ifstream status("/proc/self/status");
  std::string key;
  std::size_t kilobytes;
  while (status >> key)
  {
    if (key == field + ":" && status >> kilobytes)
    {
      return kilobytes * 1024;
    }
    status.ignore(1 << 16, '\n');
  }
  return std::nullopt;
}

/// Sets the peak (VmHWM) back to the current resident size; false where the kernel does not
/// allow it (writing 5 to clear_refs, Linux 4.0 and later).
inline bool resetPeakMemory()
{
  std::ofstream clear("/proc/self/clear_refs");
  clear << "5";
  clear.flush();
  return clear.good();
}
}
