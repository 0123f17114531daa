// Large buffers backed by transparent huge pages. Plain C++17, no VTK types.
#ifndef pcbilateral_HugePages_h
#define pcbilateral_HugePages_h

#include <algorithm>
#include <cstddef>
#include <cstdint>

namespace pcbilateral
{

/// Asks the kernel to back the whole 2 MB pages inside [data, data + bytes) with transparent
/// huge pages when they are first touched. Advice only: it does nothing off Linux.
void AdviseHugePages(void* data, std::size_t bytes);

/**
 * Makes room for `count` elements in each vector, asking the kernel to back large ones with
 * transparent huge pages before they are first touched: a run touches tens of bytes per point
 * once, and with 4 KB pages the page faults cost as much as a filter iteration (measured on a
 * virtual machine). Without huge pages, or off Linux, it is a plain reserve.
 */
template<typename... Vectors>
void ReserveWithHugePages(std::size_t count, Vectors&... vectors)
{
  auto reserve = [count](auto& vector)
  {
    if (vector.capacity() < count)
    {
      vector.clear();
      vector.reserve(count);
      AdviseHugePages(vector.data(), count * sizeof(vector[0]));
    }
  };
  (reserve(vectors), ...);
}

/**
 * Writes one element per 4 KB page of fresh memory, 2 MB at a time on `threads` threads, each
 * block after `stopSeen()` said go on (a phase's abort). Every element is written again later: this
 * only takes the page faults, in which the kernel clears each new page, a block at a time, ahead of
 * a scatter that would take them all at once (the octree's: its first few thousand points reach
 * every bucket, so every page of its 640 MB for 20 million points, and its first check came 1.6
 * to 3.2 s later on a busy virtual machine; perf: the time in clear_page).
 */
template<typename T, typename StopSeen>
void TouchPages(T* data, std::size_t count, int threads, const StopSeen& stopSeen)
{
  constexpr std::size_t PerPage = 4096 / sizeof(T) > 0 ? 4096 / sizeof(T) : 1;
  constexpr std::size_t PerBlock = (std::size_t(1) << 21) / sizeof(T);
  const auto blocks = static_cast<std::int64_t>((count + PerBlock - 1) / PerBlock);
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
  for (std::int64_t block = 0; block < blocks; ++block)
  {
    if (stopSeen())
    {
      continue;
    }
    const std::size_t end = std::min(count, static_cast<std::size_t>(block + 1) * PerBlock);
    for (std::size_t i = static_cast<std::size_t>(block) * PerBlock; i < end; i += PerPage)
    {
      data[i] = T();
    }
  }
}

} // namespace pcbilateral

#endif
