#pragma once
// A std::vector whose resize() leaves new elements of a trivial type
// uninitialized: for large buffers that are written in full right after
// they grow (a zero fill first would be a pass over memory that nothing
// reads). Elements given a value (resize(n, v), push_back, assign) are
// initialized as usual.
#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

namespace rc {

// std::allocator, except that value-initialization (construct with no
// arguments) becomes default-initialization.
template <class T>
class DefaultInitAllocator : public std::allocator<T> {
 public:
  template <class U>
  struct rebind {
    using other = DefaultInitAllocator<U>;
  };
  DefaultInitAllocator() = default;
  template <class U>
  DefaultInitAllocator(const DefaultInitAllocator<U>&) noexcept {}

  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

template <class T>
using UninitializedVector = std::vector<T, DefaultInitAllocator<T>>;

}  // namespace rc
