// The RT-unit model's per-query term for ray records (ray_query_cycles.h):
// the AVX-512 and AVX2 lanes and the one-query-at-a-time loop against the
// definition, for one and several units' costs at once, on queries with and
// without nodes, every exit value, and warps that fill the lanes' last step
// or not.
#include "backends/ray_query_cycles.h"

#include <algorithm>
#include <random>
#include <stdexcept>
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
  RayQueryArrays arrays;
};

// `count` random queries; exits 0..exits-1, kNoExit, none for no nodes.
Queries RandomQueries(std::size_t count, int exits, std::uint32_t seed) {
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
  q.arrays.fetch_offsets = q.offsets.data();
  q.arrays.last_exits = q.last_exits.data();
  q.arrays.memory_cycles = q.memory.data();
  q.arrays.exits = exits;
  return q;
}

// Unit k's costs: distinct per unit, entries from `exits` on a quiet pass.
RayPassCosts UnitCosts(int k, int exits, std::uint64_t quiet_pass_cycles) {
  RayPassCosts c;
  c.once_cycles = 17 + 5 * static_cast<std::uint64_t>(k);
  c.quiet_pass_cycles = quiet_pass_cycles + static_cast<std::uint64_t>(k);
  c.last_pass_cycles.fill(c.quiet_pass_cycles);
  for (int j = 0; j < exits; ++j) c.last_pass_cycles[j] = 11 + 7 * static_cast<std::uint64_t>(j) + 3 * k;
  return c;
}

// The definition, written out: a query's cycles and passes from its nodes
// and its last exit.
std::uint64_t Expected(const Queries& q, const RayPassCosts& c, std::size_t lo, std::size_t hi, RayPassTally* tally) {
  std::uint64_t slowest = 0;
  for (std::size_t i = lo; i < hi; ++i) {
    const std::uint64_t nodes = q.offsets[i + 1] - q.offsets[i];
    std::uint64_t cycles = c.once_cycles + q.memory[i];
    const std::uint8_t e = q.last_exits[i];
    const bool exits = nodes > 0 && e < q.arrays.exits;
    const std::uint64_t quiet = exits ? nodes - 1 : nodes;
    cycles += quiet * c.quiet_pass_cycles + (exits ? c.last_pass_cycles[e] : 0);
    if (tally) {
      tally->quiet += quiet;
      if (exits) ++tally->exit[e];
    }
    slowest = std::max(slowest, cycles);
  }
  return slowest;
}

using Form = void (*)(const RayQueryArrays&, const RayPassCosts*, int, std::size_t, std::size_t, std::uint64_t*,
                      RayPassTally&);

TEST(RayQueryCycles, EveryFormGivesEachUnitsSlowestQueryAndThePassesOnce) {
  std::vector<std::pair<const char*, Form>> forms = {{"scalar", SlowestRayQueriesScalar},
                                                     {"dispatched", SlowestRayQueries}};
  if (CpuHasAvx512()) forms.push_back({"avx512", SlowestRayQueriesLanes});
  if (CpuHasAvx2()) forms.push_back({"avx2", SlowestRayQueriesAvx2});
  // Ray programs have two exits; nine takes the AVX-512 form's gather, and
  // a quiet pass beyond 32 bits the 64-bit products (AVX2: the scalar loop).
  for (const auto& [exits, quiet_pass_cycles] :
       {std::pair<int, std::uint64_t>{1, 9}, {2, 9}, {3, 9}, {9, 9}, {2, (std::uint64_t{1} << 33) + 5}}) {
    const Queries q = RandomQueries(1000, exits, 7u + static_cast<std::uint32_t>(exits));
    for (int units : {1, 4, kMaxRayCostsPerPass}) {
      std::vector<RayPassCosts> costs;
      for (int k = 0; k < units; ++k) costs.push_back(UnitCosts(k, exits, quiet_pass_cycles));
      // Warps of 32, then ranges that leave the lanes' last step part full.
      for (std::size_t width : {std::size_t{32}, std::size_t{1}, std::size_t{7}, std::size_t{13}}) {
        for (const auto& [name, form] : forms) {
          RayPassTally want, got;
          for (std::size_t lo = 0; lo < q.last_exits.size(); lo += width) {
            const std::size_t hi = std::min(q.last_exits.size(), lo + width);
            std::uint64_t slowest[kMaxRayCostsPerPass];
            form(q.arrays, costs.data(), units, lo, hi, slowest, got);
            for (int k = 0; k < units; ++k)
              EXPECT_EQ(slowest[k], Expected(q, costs[k], lo, hi, k == 0 ? &want : nullptr))
                  << name << " unit " << k << " at " << lo;
          }
          EXPECT_GT(want.quiet, 0u);
          EXPECT_EQ(got.quiet, want.quiet) << name;
          for (int j = 0; j < exits; ++j) EXPECT_EQ(got.exit[j], want.exit[j]) << name << " exit " << j;
        }
      }
    }
  }
  if (!CpuHasAvx512())
    GTEST_SKIP() << "this host has no AVX-512: the one-query-at-a-time form" << (CpuHasAvx2() ? " and AVX2" : "")
                 << " were checked";
}

TEST(RayQueryCycles, AnEmptyRangeIsZeroAndTheUnitCountIsChecked) {
  const Queries q = RandomQueries(40, 2, 3);
  const std::vector<RayPassCosts> costs(kMaxRayCostsPerPass + 1, UnitCosts(0, 2, 9));
  std::uint64_t slowest[kMaxRayCostsPerPass + 1];
  RayPassTally tally;
  std::fill(slowest, slowest + 2, 99);
  SlowestRayQueries(q.arrays, costs.data(), 2, 5, 5, slowest, tally);
  EXPECT_EQ(slowest[0], 0u);
  EXPECT_EQ(slowest[1], 0u);
  EXPECT_EQ(tally.quiet, 0u);
  EXPECT_THROW(SlowestRayQueries(q.arrays, costs.data(), 0, 0, 8, slowest, tally), std::invalid_argument);
  EXPECT_THROW(SlowestRayQueries(q.arrays, costs.data(), kMaxRayCostsPerPass + 1, 0, 8, slowest, tally),
               std::invalid_argument);
}

}  // namespace
}  // namespace rc
