// Large buffers backed by transparent huge pages. Plain C++17, no VTK types.
#ifndef pcbilateral_HugePages_h
#define pcbilateral_HugePages_h

#include <cstddef>

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

} // namespace pcbilateral

#endif
