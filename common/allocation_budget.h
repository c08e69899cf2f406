#pragma once
// A bound on what a third-party parser may allocate. MRPT, OctoMap, OpenCV
// and yaml-cpp size their buffers from the counts a file declares, before
// they find out the file is too short; a corrupt 80-byte archive can make
// MRPT allocate gigabytes (tests/fuzz). While an AllocationBudget is alive,
// every operator new on its thread adds the bytes it requests (frees are not
// subtracted), and the request that would pass the budget throws
// std::bad_alloc, which the parser's caller reports as an InputError naming
// the file. Third-party code is reached through the global operator new,
// which this file replaces (allocation_budget.cc); without a live budget it
// is plain malloc.
#include <cstdint>
#include <exception>
#include <stdexcept>

namespace rc {

class AllocationBudget {
 public:
  explicit AllocationBudget(std::uint64_t bytes);
  ~AllocationBudget();
  AllocationBudget(const AllocationBudget&) = delete;
  AllocationBudget& operator=(const AllocationBudget&) = delete;

  // True once a request was refused.
  bool exceeded() const;
  std::uint64_t requested_bytes() const;

 private:
  std::uint64_t previous_limit_;
  std::uint64_t previous_requested_;
  bool previous_exceeded_;
};

// Thrown by ParseWithinBudget when a request was refused.
class AllocationBudgetExceeded : public std::runtime_error {
 public:
  explicit AllocationBudgetExceeded(std::uint64_t budget_bytes)
      : std::runtime_error("allocation budget exceeded"), budget_bytes_(budget_bytes) {}
  std::uint64_t budget_bytes() const { return budget_bytes_; }

 private:
  std::uint64_t budget_bytes_;
};

// Runs parse() under a budget of `bytes` and lets any exception out only
// after the budget has ended, so that the caller can build its message:
// AllocationBudgetExceeded when a request was refused (whatever the parser
// made of the std::bad_alloc), else the parser's own exception. (Handling
// the exception while the exhausted budget is still alive fails every
// allocation of the handler too: a tests/fuzz finding.)
template <typename Parse>
void ParseWithinBudget(std::uint64_t bytes, Parse&& parse) {
  std::exception_ptr error;
  bool exceeded = false;
  {
    const AllocationBudget budget(bytes);
    try {
      parse();
    } catch (...) {
      error = std::current_exception();
      exceeded = budget.exceeded();
    }
  }
  if (exceeded) throw AllocationBudgetExceeded(bytes);
  if (error) std::rethrow_exception(error);
}

// The budget for parsing a file of `file_bytes` bytes: a parser needs about
// as much memory as the data it reads, plus containers' growth and
// bookkeeping, so kParseBytesPerFileByte per byte on top of kParseBaseBytes;
// never more than the memory cap (memory_cap.h).
// kParseBytesPerFileByte: 32, range [8, 256]. Source: a valid MRPT rawlog
// holds floats and doubles that become floats and doubles in memory (1x),
// std::vector doubles its capacity while it grows (2x), and each object adds
// a shared_ptr and a vtable (about 4x for the smallest 2D scans); 32 leaves
// a wide margin and still refuses a count of 10^9 in a kilobyte file.
// kParseBaseBytes: 64 MiB, the parsers' fixed tables and buffers.
inline constexpr std::uint64_t kParseBytesPerFileByte = 32;
inline constexpr std::uint64_t kParseBaseBytes = 64ULL << 20;
std::uint64_t ParseBudgetBytes(std::uint64_t file_bytes);

}  // namespace rc
