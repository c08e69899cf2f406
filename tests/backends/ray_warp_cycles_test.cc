// The RT units' per-warp cycles of a ray record (ray_warp_cycles.h): one
// pass for many units' costs gives each unit what a pass of its own gives,
// also past the most costs one pass takes, and every SM's passes add up to
// the record's.
#include "backends/ray_warp_cycles.h"

#include <vector>

#include <gtest/gtest.h>

#include "backends/memory_replay.h"
#include "test_scenes.h"

namespace rc {
namespace {

RayPassCosts UnitCosts(int k) {
  RayPassCosts c;
  c.once_cycles = 40 + static_cast<std::uint64_t>(k);
  c.quiet_pass_cycles = 9 + 2 * static_cast<std::uint64_t>(k);
  c.last_pass_cycles.fill(c.quiet_pass_cycles);
  c.last_pass_cycles[kRayHitReturn] = 5 + static_cast<std::uint64_t>(k);
  c.last_pass_cycles[kRayEndReturn] = 7 + 3 * static_cast<std::uint64_t>(k);
  return c;
}

TEST(RayWarpCycles, OnePassForManyUnitsGivesEachWhatItsOwnPassGives) {
  const KernelRecord record =
      test::RecordedFan(test::RoomGrid(60, 60, 0.1, 0.05, 31), RayCastMethod::kMarch, 20, 20, 5.0, 32);
  ASSERT_TRUE(record.exits_per_query());
  GpuParams gpu;
  gpu.sms = 3;
  const MemoryCycles memory = ReplayMemory(record, gpu, AccessPattern{4, false}).query_memory_cycles;
  std::vector<RayPassCosts> costs;
  for (int k = 0; k < kMaxRayCostsPerPass + 3; ++k) costs.push_back(UnitCosts(k));
  const std::vector<RayWarpCycles> together = CountRayWarpCycles(record, gpu, 2, memory, costs);
  ASSERT_EQ(together.size(), costs.size());
  std::uint64_t quiet = 0, hit = 0, end = 0;
  for (std::size_t q = 0; q < record.query_count(); ++q) {
    quiet += record.QuietPasses(q);
    if (record.LastPassExits(q)) ++(record.last_exits[q] == kRayHitReturn ? hit : end);
  }
  for (std::size_t k = 0; k < costs.size(); ++k) {
    const RayWarpCycles alone = CountRayWarpCycles(record, gpu, 2, memory, {costs[k]}).front();
    EXPECT_EQ(together[k].slowest, alone.slowest) << k;
    EXPECT_EQ(together[k].sm_passes, alone.sm_passes) << k;
    ASSERT_EQ(alone.sm_passes.size(), 3u * 3u);
    std::uint64_t sums[3] = {0, 0, 0};
    for (int sm = 0; sm < 3; ++sm)
      for (int v = 0; v < 3; ++v) sums[v] += alone.sm_passes[static_cast<std::size_t>(sm) * 3 + v];
    EXPECT_EQ(sums[0], quiet);
    EXPECT_EQ(sums[1], hit);
    EXPECT_EQ(sums[2], end);
  }
  EXPECT_NE(together[0].slowest, together[1].slowest);
}

}  // namespace
}  // namespace rc
