#pragma once
// The per-query term of the RT-unit model (rt_unit_model.h) for a ray
// record, whose queries keep one exit each (kernel_record.h: every loop
// pass but the last has none). A query costs its once-per-query sections,
// its node fetches' memory cycles, a quiet pass for every node but the last,
// and its last pass at its exit (a quiet pass for kNoExit); a query without
// nodes makes no pass. Per warp the model needs the slowest query, and per
// SM the passes by exit.
//
// Integer sums and maxima: the AVX-512 and AVX2 lanes (where the host has
// them) and the one-query-at-a-time loop give the same numbers
// (tests/backends/ray_query_cycles_test.cc).
#include <array>
#include <cstddef>
#include <cstdint>

namespace rc {

struct RayQueryTerms {
  const std::uint64_t* fetch_offsets = nullptr;  // the record's, queries + 1
  const std::uint8_t* last_exits = nullptr;      // the record's, per query
  const std::uint64_t* memory_cycles = nullptr;  // per query
  std::uint64_t once_cycles = 0;                 // the once-per-query sections
  std::uint64_t quiet_pass_cycles = 0;           // a loop pass without exit
  // The cycles of a last pass, by its exit: RETURN_IF j at j < exits, a
  // quiet pass for any other value (kNoExit).
  std::array<std::uint64_t, 256> last_pass_cycles{};
  int exits = 0;  // the program's RETURN_IFs (at most 255)
};

// Passes counted over queries: those without exit, and per RETURN_IF j.
struct RayPassTally {
  std::uint64_t quiet = 0;
  std::array<std::uint64_t, 256> exit{};
};

// The slowest of queries [lo, hi); adds their passes to `tally`.
std::uint64_t SlowestRayQuery(const RayQueryTerms& terms, std::size_t lo, std::size_t hi, RayPassTally& tally);

// The same, one query at a time; in AVX-512 lanes, only where the host has
// them (CpuHasAvx512(), common/cpu_features.h); and in AVX2 lanes, only
// where it has AVX2 (CpuHasAvx2()). SlowestRayQuery takes the widest in
// use (UseAvx512(), UseAvx2()).
std::uint64_t SlowestRayQueryScalar(const RayQueryTerms& terms, std::size_t lo, std::size_t hi, RayPassTally& tally);
std::uint64_t SlowestRayQueryLanes(const RayQueryTerms& terms, std::size_t lo, std::size_t hi, RayPassTally& tally);
std::uint64_t SlowestRayQueryAvx2(const RayQueryTerms& terms, std::size_t lo, std::size_t hi, RayPassTally& tally);

}  // namespace rc
