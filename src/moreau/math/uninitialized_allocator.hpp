#pragma once
// An allocator whose vectors grow without writing zeros: resize() leaves new elements of trivial
// types uninitialised. For arrays that are grown in one call and then filled slot by slot (in
// parallel), where zeroing first would cost a second pass over the memory.
#include <memory>
#include <new>
#include <utility>

namespace moreau {

template <class T>
struct UninitializedAllocator : std::allocator<T> {
  using value_type = T;
  template <class U>
  struct rebind {
    using other = UninitializedAllocator<U>;
  };
  UninitializedAllocator() = default;
  template <class U>
  UninitializedAllocator(const UninitializedAllocator<U>&) noexcept {}

  template <class U>
  void construct(U* p) noexcept {  // default-initialisation: nothing written for doubles
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

}  // namespace moreau
