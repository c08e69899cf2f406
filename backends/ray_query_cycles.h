#pragma once
// The per-query term of the RT-unit model (rt_unit_model.h) for a ray
// record, whose queries keep one exit each (kernel_record.h: every loop
// pass but the last has none). A query costs its once-per-query sections,
// its node fetches' memory cycles, a quiet pass for every node but the last,
// and its last pass at its exit (a quiet pass for kNoExit); a query without
// nodes makes no pass. Per warp the model needs the slowest query, and per
// SM the passes by exit.
//
// The RT units that price one record (ttaplus, -p, -cr, robocore) read the
// same arrays and differ only in their costs, so one pass over the queries
// serves several units at once: the arrays are read once, which is what
// the pass is bound by once a launch's arrays outgrow the host's L2.
//
// Integer sums and maxima: the AVX-512 and AVX2 lanes (where the host has
// them) and the one-query-at-a-time loop give the same numbers
// (tests/backends/ray_query_cycles_test.cc).
#include <array>
#include <cstddef>
#include <cstdint>

namespace rc {

// What the record gives: the same for every unit pricing it.
struct RayQueryArrays {
  const std::uint64_t* fetch_offsets = nullptr;  // the record's, queries + 1
  const std::uint8_t* last_exits = nullptr;      // the record's, per query
  const std::uint64_t* memory_cycles = nullptr;  // per query (the memory replay's)
  int exits = 0;                                 // the program's RETURN_IFs (at most 255)
};

// What one unit's datapath makes of a query's passes, in cycles.
struct RayPassCosts {
  std::uint64_t once_cycles = 0;        // the once-per-query sections
  std::uint64_t quiet_pass_cycles = 0;  // a loop pass without exit
  // The cycles of a last pass, by its exit: RETURN_IF j at j < exits, a
  // quiet pass for any other value (kNoExit).
  std::array<std::uint64_t, 256> last_pass_cycles{};

  bool operator==(const RayPassCosts& other) const {
    return once_cycles == other.once_cycles && quiet_pass_cycles == other.quiet_pass_cycles &&
           last_pass_cycles == other.last_pass_cycles;
  }
};

// Passes counted over queries: those without exit, and per RETURN_IF j.
struct RayPassTally {
  std::uint64_t quiet = 0;
  std::array<std::uint64_t, 256> exit{};
};

// The most units one pass serves.
inline constexpr int kMaxRayCostsPerPass = 8;

// For each of `count` units (1 <= count <= kMaxRayCostsPerPass),
// slowest[k] = the slowest of queries [lo, hi) under costs[k] (0 for an
// empty range); adds the queries' passes, which do not depend on the costs,
// to `tally` once.
void SlowestRayQueries(const RayQueryArrays& arrays, const RayPassCosts* costs, int count, std::size_t lo,
                       std::size_t hi, std::uint64_t* slowest, RayPassTally& tally);

// The same, one query at a time; in AVX-512 lanes, only where the host has
// them (CpuHasAvx512(), common/cpu_features.h); and in AVX2 lanes, only
// where it has AVX2 (CpuHasAvx2()). SlowestRayQueries takes the widest in
// use (UseAvx512(), UseAvx2()).
void SlowestRayQueriesScalar(const RayQueryArrays& arrays, const RayPassCosts* costs, int count, std::size_t lo,
                             std::size_t hi, std::uint64_t* slowest, RayPassTally& tally);
void SlowestRayQueriesLanes(const RayQueryArrays& arrays, const RayPassCosts* costs, int count, std::size_t lo,
                            std::size_t hi, std::uint64_t* slowest, RayPassTally& tally);
void SlowestRayQueriesAvx2(const RayQueryArrays& arrays, const RayPassCosts* costs, int count, std::size_t lo,
                           std::size_t hi, std::uint64_t* slowest, RayPassTally& tally);

}  // namespace rc
