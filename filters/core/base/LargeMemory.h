#pragma once
// Memory for large arrays, backed by transparent huge pages where Linux gives them on request
// (/sys/kernel/mm/transparent_hugepage/enabled set to "madvise", Debian's default). Newly
// allocated memory is mapped page by page as it is first written: with 4 kB pages a 120 MB
// array costs 30,000 page faults, which on this project's 2-core virtual machine took 260 to
// 480 ms, twenty times the shading itself; with 2 MB pages it costs 60 and took 6 to 11 ms.
#include <cstddef>
#include <cstdlib>
#include <new>

namespace shadelab
{
/// `bytes` of uninitialised memory, to be released with std::free; nullptr when there is not
/// enough memory. Blocks of 4 MB or more are aligned to 2 MB and marked for huge pages.
void* allocateLarge(std::size_t bytes);

/// A std::vector allocator that takes its memory from allocateLarge.
template<typename T>
struct LargeAllocator
{
  using value_type = T;

  LargeAllocator() = default;
  template<typename U>
  LargeAllocator(const LargeAllocator<U>&) noexcept
  {
  }

  T* allocate(std::size_t count)
  {
    void* memory = count <= std::size_t(-1) / sizeof(T) ? allocateLarge(count * sizeof(T)) : nullptr;
    if (!memory)
    {
      throw std::bad_alloc();
    }
    return static_cast<T*>(memory);
  }
  void deallocate(T* memory, std::size_t) noexcept { std::free(memory); }

  template<typename U>
  bool operator==(const LargeAllocator<U>&) const noexcept
  {
    return true;
  }
  template<typename U>
  bool operator!=(const LargeAllocator<U>&) const noexcept
  {
    return false;
  }
};
}
