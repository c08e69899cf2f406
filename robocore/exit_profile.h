#pragma once
// Per query, how many of its loop passes ended at each exit (RETURN_IF):
// what the RT units' cost models price a query's passes by, in O(variants)
// instead of O(nodes). ProfileExits (backends/memory_replay.h) makes it from
// a record's exits; a recorder may tally it as the kernel runs instead
// (KernelRecord::tallied_exits), so that no per-fetch exit is stored.
#include <array>
#include <cstdint>
#include <vector>

#include "robocore/section_timing.h"

namespace rc {

// Pairs of (variant, passes) in CSR form, variant 0 = no exit, 1 + j =
// RETURN_IF j. A query's pairs come "no exit" first (most passes have
// none), then the exits in the order the query first met them. A ray has at
// most two variants (every pass but the last has none).
struct ExitProfile {
  std::vector<std::uint32_t> offsets{0};  // per query + 1
  std::vector<std::uint8_t> variant;
  std::vector<std::uint32_t> passes;
};

// One query's passes tallied by exit (kNoExit or a RETURN_IF index), then
// appended to a profile's lists in ExitProfile's order. Reused query after
// query: Append leaves it empty.
class ExitTally {
 public:
  void Add(std::uint8_t exit) {
    if (count_[exit]++ == 0) seen_[distinct_++] = exit;
  }
  // Appends this query's pairs to `variant` and `passes` (vectors, or
  // anything with push_back) and returns how many.
  template <class Variants, class Passes>
  std::uint32_t Append(Variants& variant, Passes& passes) {
    std::uint32_t pairs = 0;
    if (count_[kNoExit] > 0) {
      variant.push_back(0);
      passes.push_back(count_[kNoExit]);
      count_[kNoExit] = 0;
      ++pairs;
    }
    for (std::uint32_t i = 0; i < distinct_; ++i) {
      const std::uint8_t e = seen_[i];
      if (e == kNoExit) continue;
      variant.push_back(static_cast<std::uint8_t>(1 + e));
      passes.push_back(count_[e]);
      count_[e] = 0;
      ++pairs;
    }
    distinct_ = 0;
    return pairs;
  }

 private:
  std::array<std::uint32_t, 256> count_{};
  std::array<std::uint8_t, 256> seen_{};
  std::uint32_t distinct_ = 0;
};

}  // namespace rc
