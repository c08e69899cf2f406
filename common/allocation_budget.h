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
