#include "LargeMemory.h"

#include <cstdlib>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace shadelab
{
void* allocateLarge(std::size_t bytes)
{
  constexpr std::size_t hugePage = std::size_t(2) << 20;
  if (bytes < 2 * hugePage)
  {
    return std::malloc(bytes > 0 ? bytes : 1);
  }
  void* memory = nullptr;
  if (posix_memalign(&memory, hugePage, bytes) != 0)
  {
    return nullptr;
  }
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  // Advice only: where the kernel has no huge pages the memory is simply used as it is.
  madvise(memory, bytes, MADV_HUGEPAGE);
#endif
  return memory;
}
}
