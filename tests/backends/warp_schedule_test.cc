// The list scheduling of warps onto slots (warp_schedule.h) and the warps'
// placement on SMs (memory_replay.h), each against its definition.
#include "backends/warp_schedule.h"

#include <algorithm>
#include <cstdint>
#include <functional>
#include <queue>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "backends/gpu_params.h"
#include "backends/memory_replay.h"

namespace rc {
namespace {

// The definition: each warp, in order, takes the slot that frees first.
std::uint64_t MakespanByQueue(const std::vector<std::uint64_t>& durations, int slots) {
  std::priority_queue<std::uint64_t, std::vector<std::uint64_t>, std::greater<>> free_at;
  for (int i = 0; i < slots; ++i) free_at.push(0);
  std::uint64_t end = 0;
  for (std::uint64_t d : durations) {
    const std::uint64_t start = free_at.top();
    free_at.pop();
    free_at.push(start + d);
    end = std::max(end, start + d);
  }
  return end;
}

TEST(WarpSchedule, SmallCasesByHand) {
  EXPECT_EQ(Makespan({}, 4), 0u);
  EXPECT_EQ(Makespan({5, 3, 9}, 4), 9u);       // fewer warps than slots
  EXPECT_EQ(Makespan({5, 3, 9}, 1), 17u);      // one slot: the sum
  EXPECT_EQ(Makespan({4, 4, 4, 4}, 2), 8u);    // two rounds of two
  EXPECT_EQ(Makespan({10, 1, 1, 1}, 2), 10u);  // the short ones share a slot
  EXPECT_EQ(Makespan({1, 1, 10}, 2), 11u);     // the long one comes last
}

TEST(WarpSchedule, MakespanIsTheQueuesAtEverySlotCount) {
  std::mt19937_64 rng(11);
  for (int slots : {1, 2, 3, 7, 8, 16, 33, 64}) {
    for (std::size_t n : {0, 1, 5, 63, 64, 65, 1000}) {
      std::vector<std::uint64_t> durations(n);
      // Many equal durations (ties between slots), and some large ones.
      for (std::uint64_t& d : durations) d = rng() % 4 == 0 ? rng() % (1u << 30) : rng() % 8;
      EXPECT_EQ(Makespan(durations, slots), MakespanByQueue(durations, slots)) << slots << " slots, " << n << " warps";
    }
  }
}

TEST(WarpSchedule, WarpsBySmDealsBlocksRoundRobin) {
  for (int sms : {1, 3, 8}) {
    for (int per_block : {1, 4, 8}) {
      GpuParams gpu;
      gpu.sms = sms;
      gpu.warps_per_block = per_block;
      for (std::size_t warps : {0, 1, 7, 8, 9, 100, 257}) {
        const std::vector<std::vector<std::uint32_t>> lists = WarpsBySm(warps, gpu);
        ASSERT_EQ(lists.size(), static_cast<std::size_t>(sms));
        std::vector<std::vector<std::uint32_t>> expected(static_cast<std::size_t>(sms));
        for (std::size_t w = 0; w < warps; ++w)
          expected[static_cast<std::size_t>(SmOfWarp(w, gpu))].push_back(static_cast<std::uint32_t>(w));
        EXPECT_EQ(lists, expected) << sms << " SMs, " << per_block << " warps a block, " << warps << " warps";
      }
    }
  }
}

}  // namespace
}  // namespace rc
