#pragma once
// The per-thread step of the sampled replay's estimate (memory_replay.cc,
// EstimateUnsampled): the lanes of a warp whose addresses were not kept
// each borrow their partner's memory cycles per node, the partner found by
// the lane's rank of node count. Lane i's cycles become
//   l1_latency * nodes[i] + round(rate[rank[i]] * nodes[i])   (rank[i] < rate_count)
//   l1_latency * nodes[i] + round(fallback * nodes[i])        (otherwise)
// (what every fetch pays, then what the partner paid beyond it), rounding
// a non-negative product below 2^63 half up (as llround does) and any
// other with llround itself. Written whole in one pass: a separate pass
// writing the L1 share first, which this one then read back, showed in
// profiles.
//
// Every form gives the same cycles: the products are the same IEEE
// multiplications, and the rounding is exact
// (tests/backends/borrowed_cycles_test.cc).
#include <cmath>
#include <cstddef>
#include <cstdint>

namespace rc {

// cycles += llround(extra), inline for a non-negative extra below 2^63
// (every one the estimate gives in practice): truncation is the floor, and
// extra - floor(extra) is exact (below 2^53 by Sterbenz's lemma; above,
// extra is whole), so a half rounds up as llround's does. Through the
// signed conversion, one instruction (the unsigned one is a branch and a
// subtraction without AVX-512).
inline void AddRoundedCycles(std::uint64_t& cycles, double extra) {
  if (!(extra >= 0.0 && extra < 0x1p63)) {
    cycles += static_cast<std::uint64_t>(std::llround(extra));
    return;
  }
  const auto whole = static_cast<std::int64_t>(extra);
  cycles += static_cast<std::uint64_t>(whole) + static_cast<std::uint64_t>(extra - static_cast<double>(whole) >= 0.5);
}

void WriteBorrowedCycles(const std::uint32_t* rank, const std::uint32_t* nodes, std::size_t count, const double* rate,
                         std::size_t rate_count, double fallback, std::uint64_t l1_latency, std::uint64_t* cycles);

// The same, lane by lane; and eight lanes at a time in AVX-512, only where
// the host has it (CpuHasAvx512(), common/cpu_features.h).
// WriteBorrowedCycles takes the AVX-512 form where it is in use (UseAvx512()).
void WriteBorrowedCyclesScalar(const std::uint32_t* rank, const std::uint32_t* nodes, std::size_t count,
                               const double* rate, std::size_t rate_count, double fallback, std::uint64_t l1_latency,
                               std::uint64_t* cycles);
void WriteBorrowedCyclesLanes(const std::uint32_t* rank, const std::uint32_t* nodes, std::size_t count,
                              const double* rate, std::size_t rate_count, double fallback, std::uint64_t l1_latency,
                              std::uint64_t* cycles);

}  // namespace rc
