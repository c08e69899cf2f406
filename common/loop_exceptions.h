#pragma once
// An exception may not leave an OpenMP loop or task: the process would end.
// A loop whose iterations may throw runs each body through Run, which keeps
// what it throws in that iteration's slot; after the loop, RethrowFirst
// rethrows the exception of the lowest iteration that threw, so that the
// caller sees the same one at any thread count.
#include <cstddef>
#include <exception>
#include <vector>

namespace rc {

class LoopExceptions {
 public:
  explicit LoopExceptions(std::size_t iterations) : caught_(iterations) {}

  template <class Body>
  void Run(std::size_t iteration, Body&& body) noexcept {
    try {
      body();
    } catch (...) {
      caught_[iteration] = std::current_exception();
    }
  }

  void RethrowFirst() const {
    for (const std::exception_ptr& e : caught_)
      if (e) std::rethrow_exception(e);
  }

 private:
  std::vector<std::exception_ptr> caught_;
};

}  // namespace rc
