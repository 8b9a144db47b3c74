#pragma once
// Vectors whose memory is given back early or left unzeroed: for the large arrays of the
// methods, where a copy held too long or a zeroing pass on one thread costs what the work does.

#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

namespace rad {

/// Gives a vector's memory back now, before it goes out of scope: `v = {}` (an initializer-list
/// assignment) and `v.clear()` keep its capacity.
template <typename T, typename A>
void releaseMemory(std::vector<T, A>& v) {
  std::vector<T, A>().swap(v);
}

/// An allocator whose resize leaves trivially constructible elements uninitialized: for large
/// arrays filled in parallel right after, which zeroing on one thread first would slow as much
/// as the fill itself (and fault every page in on that one thread).
template <class T>
struct UninitializedAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = UninitializedAllocator<U>;
  };
  UninitializedAllocator() = default;
  template <class U>
  UninitializedAllocator(const UninitializedAllocator<U>&) noexcept {}
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};
/// A vector that resize() does not zero (UninitializedAllocator).
template <class T>
using FilledLaterVector = std::vector<T, UninitializedAllocator<T>>;

}  // namespace rad
