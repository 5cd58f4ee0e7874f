// std::allocator, except that resize() leaves the new elements uninitialised, for buffers written in full
// before they are read: a decoded image (zero-filling a 4096² atlas's 50 MB first, on one core, then the
// decoders' own writes, was ~50 M instructions and every page fault on the loading thread) and a frame's
// per-pixel buffers (9 MB a 640×360 frame, 3 % of a draft frame's instructions).
#pragma once

#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

namespace cinepath::preview {

template <typename T>
struct UninitializedAllocator : std::allocator<T> {
  template <typename U>
  struct rebind {
    using other = UninitializedAllocator<U>;
  };
  UninitializedAllocator() = default;
  template <typename U>
  UninitializedAllocator(const UninitializedAllocator<U>&) noexcept {}
  template <typename U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};
template <typename T>
using UninitializedVector = std::vector<T, UninitializedAllocator<T>>;

}  // namespace cinepath::preview
