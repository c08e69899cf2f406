// The RT units' per-warp cycles (rt_warp_cycles.h): one pass for many
// units' costs gives each unit what a pass of its own gives, also past the
// most costs one pass takes, and every SM's passes add up to the record's;
// from an exit profile, each warp's slowest query is the one a direct sum
// over its pairs finds.
#include "backends/rt_warp_cycles.h"

#include <algorithm>
#include <random>
#include <stdexcept>
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

TEST(UnitWarpCycles, OnePassForManyUnitsGivesEachWhatItsOwnPassGives) {
  const KernelRecord record =
      test::RecordedFan(test::RoomGrid(60, 60, 0.1, 0.05, 31), RayCastMethod::kMarch, 20, 20, 5.0, 32);
  ASSERT_TRUE(record.exits_per_query());
  GpuParams gpu;
  gpu.sms = 3;
  const MemoryCycles memory = ReplayMemory(record, gpu, AccessPattern{4, false}).query_memory_cycles;
  std::vector<RayPassCosts> costs;
  for (int k = 0; k < kMaxRayCostsPerPass + 3; ++k) costs.push_back(UnitCosts(k));
  const std::vector<UnitWarpCycles> together = CountRayWarpCycles(record, gpu, 2, memory, costs);
  ASSERT_EQ(together.size(), costs.size());
  std::uint64_t quiet = 0, hit = 0, end = 0;
  for (std::size_t q = 0; q < record.query_count(); ++q) {
    quiet += record.QuietPasses(q);
    if (record.LastPassExits(q)) ++(record.last_exits[q] == kRayHitReturn ? hit : end);
  }
  for (std::size_t k = 0; k < costs.size(); ++k) {
    const UnitWarpCycles alone = CountRayWarpCycles(record, gpu, 2, memory, {costs[k]}).front();
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

// A record of `n` queries whose exit profile has 0 to 4 pairs each, over
// variants 0..exits, with a few long queries so that warps' slowest differ.
struct ProfiledRecord {
  KernelRecord record;
  ExitProfile profile;
  MemoryCycles memory;
};

ProfiledRecord RandomProfiledRecord(std::size_t n, int exits, unsigned seed) {
  std::mt19937 rng(seed);
  ProfiledRecord r;
  r.record.fetch_offsets.assign(1, 0);
  for (std::size_t q = 0; q < n; ++q) {
    const int pairs = static_cast<int>(rng() % 5);
    std::uint64_t nodes = 0;
    for (int i = 0; i < pairs; ++i) {
      r.profile.variant.push_back(static_cast<std::uint8_t>(rng() % static_cast<unsigned>(exits + 1)));
      r.profile.passes.push_back(1 + rng() % (q % 37 == 0 ? 400 : 20));
      nodes += r.profile.passes.back();
    }
    r.profile.offsets.push_back(static_cast<std::uint32_t>(r.profile.variant.size()));
    r.record.fetch_offsets.push_back(r.record.fetch_offsets.back() + nodes);
    r.memory.push_back(rng() % 900);
  }
  return r;
}

TEST(ProfileWarpCycles, EachWarpsSlowestQueryIsTheDirectSumsAndOnePassServesManyUnits) {
  const int exits = 15;  // the SACT program's RETURN_IFs
  const ProfiledRecord r = RandomProfiledRecord(1000, exits, 7);
  GpuParams gpu;
  gpu.sms = 3;
  std::vector<RayPassCosts> costs;
  for (int k = 0; k < kMaxRayCostsPerPass + 3; ++k) {
    RayPassCosts c = UnitCosts(k);
    for (int j = 0; j < exits; ++j) c.last_pass_cycles[j] = 3 + static_cast<std::uint64_t>((j * 7 + k * 5) % 11);
    costs.push_back(c);
  }
  const std::vector<UnitWarpCycles> together = CountProfileWarpCycles(r.record, r.profile, gpu, exits, r.memory, costs);
  ASSERT_EQ(together.size(), costs.size());
  const std::size_t warps = WarpCount(r.record, gpu);
  const std::size_t n = r.record.query_count();
  for (std::size_t k = 0; k < costs.size(); ++k) {
    std::vector<std::uint64_t> slowest(warps, 0);
    for (std::size_t q = 0; q < n; ++q) {
      std::uint64_t cycles = costs[k].once_cycles + r.memory[q];
      for (std::uint32_t i = r.profile.offsets[q]; i < r.profile.offsets[q + 1]; ++i) {
        const std::uint8_t v = r.profile.variant[i];
        cycles += r.profile.passes[i] * (v == 0 ? costs[k].quiet_pass_cycles : costs[k].last_pass_cycles[v - 1]);
      }
      std::uint64_t& s = slowest[q / static_cast<std::size_t>(gpu.warp_size)];
      s = std::max(s, cycles);
    }
    EXPECT_EQ(together[k].slowest, slowest) << k;
    const UnitWarpCycles alone = CountProfileWarpCycles(r.record, r.profile, gpu, exits, r.memory, {costs[k]}).front();
    EXPECT_EQ(alone.slowest, slowest) << k;
    EXPECT_EQ(together[k].sm_passes, alone.sm_passes) << k;
  }
  // Every SM's passes by variant add up to the profile's.
  std::vector<std::uint64_t> by_variant(exits + 1, 0), summed(exits + 1, 0);
  for (std::size_t i = 0; i < r.profile.variant.size(); ++i) by_variant[r.profile.variant[i]] += r.profile.passes[i];
  for (int sm = 0; sm < gpu.sms; ++sm)
    for (int v = 0; v <= exits; ++v) summed[v] += together[0].sm_passes[static_cast<std::size_t>(sm) * (exits + 1) + v];
  EXPECT_EQ(summed, by_variant);
  EXPECT_NE(together[0].slowest, together[1].slowest);
}

TEST(ProfileWarpCycles, RefusesAnExitTheLoopDoesNotHaveAndAnotherRecordsProfile) {
  const ProfiledRecord r = RandomProfiledRecord(100, 15, 8);
  GpuParams gpu;
  EXPECT_THROW(CountProfileWarpCycles(r.record, r.profile, gpu, 3, r.memory, {UnitCosts(0)}), std::logic_error);
  const ProfiledRecord other = RandomProfiledRecord(99, 15, 8);
  EXPECT_THROW(CountProfileWarpCycles(r.record, other.profile, gpu, 15, r.memory, {UnitCosts(0)}), std::logic_error);
}

}  // namespace
}  // namespace rc
