// The RT-unit model's per-query term for ray records (ray_query_cycles.h):
// the AVX-512 and AVX2 lanes and the one-query-at-a-time loop against the
// definition, on queries with and without nodes, every exit value, and
// warps that fill the lanes' last step or not.
#include "backends/ray_query_cycles.h"

#include <algorithm>
#include <random>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "common/cpu_features.h"
#include "robocore/section_timing.h"

namespace rc {
namespace {

struct Queries {
  std::vector<std::uint64_t> offsets{0};
  std::vector<std::uint8_t> last_exits;
  std::vector<std::uint64_t> memory;
  RayQueryTerms terms;
};

// `count` random queries; exits 0..exits-1, kNoExit, none for no nodes.
Queries RandomQueries(std::size_t count, int exits, std::uint32_t seed, std::uint64_t quiet_pass_cycles = 9) {
  std::mt19937 rng(seed);
  Queries q;
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint32_t nodes = rng() % 5 == 0 ? 0 : rng() % 300;
    q.offsets.push_back(q.offsets.back() + nodes);
    const std::uint32_t pick = rng() % static_cast<std::uint32_t>(exits + 1);
    q.last_exits.push_back(nodes == 0 || pick == static_cast<std::uint32_t>(exits) ? kNoExit
                                                                                   : static_cast<std::uint8_t>(pick));
    q.memory.push_back(nodes * (20 + rng() % 400));
  }
  q.terms.fetch_offsets = q.offsets.data();
  q.terms.last_exits = q.last_exits.data();
  q.terms.memory_cycles = q.memory.data();
  q.terms.once_cycles = 17;
  q.terms.quiet_pass_cycles = quiet_pass_cycles;
  q.terms.last_pass_cycles.fill(q.terms.quiet_pass_cycles);
  q.terms.exits = exits;
  for (int j = 0; j < exits; ++j) q.terms.last_pass_cycles[j] = 11 + 7 * j;
  return q;
}

// The definition, written out: a query's cycles and passes from its nodes
// and its last exit.
std::uint64_t Expected(const Queries& q, std::size_t lo, std::size_t hi, RayPassTally& tally) {
  std::uint64_t slowest = 0;
  for (std::size_t i = lo; i < hi; ++i) {
    const std::uint64_t nodes = q.offsets[i + 1] - q.offsets[i];
    std::uint64_t cycles = q.terms.once_cycles + q.memory[i];
    const std::uint8_t e = q.last_exits[i];
    const bool exits = nodes > 0 && e < q.terms.exits;
    const std::uint64_t quiet = exits ? nodes - 1 : nodes;
    cycles += quiet * q.terms.quiet_pass_cycles + (exits ? q.terms.last_pass_cycles[e] : 0);
    tally.quiet += quiet;
    if (exits) ++tally.exit[e];
    slowest = std::max(slowest, cycles);
  }
  return slowest;
}

TEST(RayQueryCycles, BothFormsGiveTheDefinitionsSlowestQueryAndPasses) {
  // Ray programs have two exits; nine takes the AVX-512 form's gather, and
  // a quiet pass beyond 32 bits its 64-bit products.
  for (const auto& [exits, quiet_pass_cycles] :
       {std::pair<int, std::uint64_t>{1, 9}, {2, 9}, {3, 9}, {9, 9}, {2, (std::uint64_t{1} << 33) + 5}}) {
    const Queries q = RandomQueries(1000, exits, 7u + static_cast<std::uint32_t>(exits), quiet_pass_cycles);
    // Warps of 32, then ranges that leave the lanes' last step part full.
    for (std::size_t width : {std::size_t{32}, std::size_t{1}, std::size_t{7}, std::size_t{13}}) {
      RayPassTally want, scalar, lanes, avx2, dispatched;
      for (std::size_t lo = 0; lo < q.last_exits.size(); lo += width) {
        const std::size_t hi = std::min(q.last_exits.size(), lo + width);
        const std::uint64_t expected = Expected(q, lo, hi, want);
        EXPECT_EQ(SlowestRayQueryScalar(q.terms, lo, hi, scalar), expected) << lo;
        if (CpuHasAvx512()) {
          EXPECT_EQ(SlowestRayQueryLanes(q.terms, lo, hi, lanes), expected) << lo;
        }
        if (CpuHasAvx2()) {
          EXPECT_EQ(SlowestRayQueryAvx2(q.terms, lo, hi, avx2), expected) << lo;
        }
        EXPECT_EQ(SlowestRayQuery(q.terms, lo, hi, dispatched), expected) << lo;
      }
      EXPECT_GT(want.quiet, 0u);
      std::vector<const RayPassTally*> tallies = {&scalar, &dispatched};
      if (CpuHasAvx512()) tallies.push_back(&lanes);
      if (CpuHasAvx2()) tallies.push_back(&avx2);
      for (const RayPassTally* got : tallies) {
        EXPECT_EQ(got->quiet, want.quiet);
        for (int j = 0; j < exits; ++j) EXPECT_EQ(got->exit[j], want.exit[j]) << j;
      }
    }
  }
  if (!CpuHasAvx512())
    GTEST_SKIP() << "this host has no AVX-512: the one-query-at-a-time form" << (CpuHasAvx2() ? " and AVX2" : "")
                 << " were checked";
}

}  // namespace
}  // namespace rc
