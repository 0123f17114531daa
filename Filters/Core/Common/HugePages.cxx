#include "HugePages.h"

#include <cstdint>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace pcbilateral
{

void AdviseHugePages(void* data, std::size_t bytes)
{
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  // Only whole 2 MB pages inside the buffer can be huge ones.
  constexpr std::uintptr_t HugePage = std::uintptr_t{ 1 } << 21;
  const auto begin = (reinterpret_cast<std::uintptr_t>(data) + HugePage - 1) & ~(HugePage - 1);
  const auto end = (reinterpret_cast<std::uintptr_t>(data) + bytes) & ~(HugePage - 1);
  if (end > begin)
  {
    madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE); // advice only
  }
#else
  (void)data;
  (void)bytes;
#endif
}

} // namespace pcbilateral
