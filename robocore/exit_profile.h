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
  // How many pairs this query appends: one per distinct exit it met.
  std::uint32_t pairs() const { return distinct_; }
  // Writes this query's pairs to variant[0, pairs()) and passes[0,
  // pairs()), which must have room, and returns how many. Raw pointers: a
  // recorder writing straight into its lists needs no reload of a vector's
  // end after every byte it stores.
  std::uint32_t Write(std::uint8_t* variant, std::uint32_t* passes) {
    std::uint32_t pairs = 0;
    if (count_[kNoExit] > 0) {
      variant[pairs] = 0;
      passes[pairs++] = count_[kNoExit];
      count_[kNoExit] = 0;
    }
    for (std::uint32_t i = 0; i < distinct_; ++i) {
      const std::uint8_t e = seen_[i];
      if (e == kNoExit) continue;
      variant[pairs] = static_cast<std::uint8_t>(1 + e);
      passes[pairs++] = count_[e];
      count_[e] = 0;
    }
    distinct_ = 0;
    return pairs;
  }
  // Appends this query's pairs to the vectors `variant` and `passes` and
  // returns how many.
  std::uint32_t Append(std::vector<std::uint8_t>& variant, std::vector<std::uint32_t>& passes) {
    const std::size_t at = variant.size();
    variant.resize(at + distinct_);
    passes.resize(at + distinct_);
    return Write(variant.data() + at, passes.data() + at);
  }

 private:
  std::array<std::uint32_t, 256> count_{};
  std::array<std::uint8_t, 256> seen_{};
  std::uint32_t distinct_ = 0;
};

}  // namespace rc
