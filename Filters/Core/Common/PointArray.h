// Per-point arrays that are not zeroed when they grow. Plain C++17.
#ifndef pcbilateral_PointArray_h
#define pcbilateral_PointArray_h

#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace pcbilateral
{

/**
 * std::allocator, except that resize() leaves new elements uninitialised instead of zeroing
 * them, for per-point arrays whose every element is written before it is read: in the octree,
 * the zeroing was a serial pass over fresh memory (its page faults included) of some 30 bytes
 * per point, 1.4 s of lidar20M's 2-thread Load and as much of its first layout; the pages are
 * now first touched where the arrays are filled, in parallel.
 */
template<typename T>
struct UninitializedAllocator : std::allocator<T>
{
  template<typename U>
  struct rebind
  {
    using other = UninitializedAllocator<U>;
  };
  UninitializedAllocator() = default;
  template<typename U>
  UninitializedAllocator(const UninitializedAllocator<U>&) noexcept
  {
  }
  template<typename U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible<U>::value)
  {
    ::new (static_cast<void*>(p)) U;
  }
  template<typename U, typename... Arguments>
  void construct(U* p, Arguments&&... arguments)
  {
    ::new (static_cast<void*>(p)) U(std::forward<Arguments>(arguments)...);
  }
};

/// A per-point array whose elements are written before they are read (see
/// UninitializedAllocator).
template<typename T>
using PointArray = std::vector<T, UninitializedAllocator<T>>;

} // namespace pcbilateral

#endif
