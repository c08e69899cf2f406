#include "common/allocation_budget.h"

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <new>

#include "common/memory_cap.h"

namespace rc {
namespace {

constexpr std::uint64_t kNoLimit = std::numeric_limits<std::uint64_t>::max();

// Per thread: OpenMP workers and other threads are never limited by a
// parser running on another thread.
thread_local std::uint64_t t_limit = kNoLimit;
thread_local std::uint64_t t_requested = 0;
thread_local bool t_exceeded = false;

// Counts a request against the live budget; false when it would pass it.
bool Admit(std::size_t size) {
  if (t_limit == kNoLimit) return true;
  if (size > t_limit - std::min(t_requested, t_limit)) {
    t_exceeded = true;
    return false;
  }
  t_requested += size;
  return true;
}

void* Allocate(std::size_t size) {
  if (!Admit(size)) throw std::bad_alloc();
  for (;;) {
    if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
    std::new_handler handler = std::get_new_handler();
    if (!handler) throw std::bad_alloc();
    handler();
  }
}

void* AllocateAligned(std::size_t size, std::align_val_t alignment) {
  if (!Admit(size)) throw std::bad_alloc();
  const std::size_t a = std::max(static_cast<std::size_t>(alignment), sizeof(void*));
  const std::size_t rounded = (std::max<std::size_t>(size, 1) + a - 1) / a * a;
  for (;;) {
    if (void* p = std::aligned_alloc(a, rounded)) return p;
    std::new_handler handler = std::get_new_handler();
    if (!handler) throw std::bad_alloc();
    handler();
  }
}

}  // namespace

AllocationBudget::AllocationBudget(std::uint64_t bytes)
    : previous_limit_(t_limit), previous_requested_(t_requested), previous_exceeded_(t_exceeded) {
  t_limit = bytes;
  t_requested = 0;
  t_exceeded = false;
}

AllocationBudget::~AllocationBudget() {
  t_limit = previous_limit_;
  t_requested = previous_requested_;
  t_exceeded = previous_exceeded_;
}

bool AllocationBudget::exceeded() const { return t_exceeded; }
std::uint64_t AllocationBudget::requested_bytes() const { return t_requested; }

std::uint64_t ParseBudgetBytes(std::uint64_t file_bytes) {
  return std::min(MemoryCapBytes(), kParseBaseBytes + BytesFor(file_bytes, kParseBytesPerFileByte));
}

}  // namespace rc

// The replaceable global allocation functions ([new.delete]): the same
// malloc-based behaviour as the library's, plus rc::AllocationBudget.
void* operator new(std::size_t size) { return rc::Allocate(size); }
void* operator new[](std::size_t size) { return rc::Allocate(size); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  try {
    return rc::Allocate(size);
  } catch (...) {
    return nullptr;
  }
}
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
  try {
    return rc::Allocate(size);
  } catch (...) {
    return nullptr;
  }
}
void* operator new(std::size_t size, std::align_val_t a) { return rc::AllocateAligned(size, a); }
void* operator new[](std::size_t size, std::align_val_t a) { return rc::AllocateAligned(size, a); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }

// MRPT's aligned containers (mrpt::aligned_allocator_cpp11: a scan's ranges,
// validity flags and intensities, point clouds) allocate through
// mrpt::aligned_malloc, which calls aligned_alloc directly, not operator new
// (a tests/fuzz finding: a 2D scan declaring 4e9 ranges asked for 16 GB
// past the budget). Defined here, in the executable, it takes the place of
// libmrpt-core's for every MRPT library that calls it (the dynamic linker
// binds the executable's definition first), so the budget sees those
// requests too. Same contract as MRPT 2.5's own: the size rounded up to a
// multiple of the alignment, aligned_alloc, nullptr when the system has no
// memory, released by mrpt::aligned_free with free(). A request the budget
// refuses throws std::bad_alloc, which the container passes on.
namespace mrpt {
void* aligned_malloc(std::size_t size, std::size_t alignment);
void* aligned_malloc(std::size_t size, std::size_t alignment) {
  if (alignment != 0 && size % alignment != 0) size = (size / alignment + 1) * alignment;
  if (!rc::Admit(size)) throw std::bad_alloc();
  return std::aligned_alloc(alignment, size);
}
}  // namespace mrpt
