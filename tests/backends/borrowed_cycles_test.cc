// The sampled estimate's borrowed cycles (borrowed_cycles.h): every form
// against the definition, the L1 latency per node plus llround of each
// lane's product, written over what the lanes held, at every count
// up to a warp and beyond, with ranks past the rates and products that
// are negative, huge or fractional halves.
#include "backends/borrowed_cycles.h"

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "common/cpu_features.h"

namespace rc {
namespace {

TEST(BorrowedCycles, RoundingIsLlroundsOnEveryExtra) {
  for (double extra : {0.0, 0.49999999999999994, 0.5, 1.5, 2.5, 1e15 + 0.5, 0x1p53, 0x1p62, 0x1p63 - 1024.0, 0x1p63,
                       -0.5, -1.5, -3.0}) {
    std::uint64_t cycles = 1000;
    AddRoundedCycles(cycles, extra);
    EXPECT_EQ(cycles, std::uint64_t{1000} + static_cast<std::uint64_t>(std::llround(extra))) << extra;
  }
}

TEST(BorrowedCycles, EveryFormWritesTheL1ShareAndEachLanesRoundedProduct) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> real(0.0, 400.0);
  for (std::size_t count = 0; count <= 70; ++count) {
    for (int variant = 0; variant < 3; ++variant) {
      // Rates as the estimate makes them (cycles per node, some exact
      // halves), and in one variant some negative or huge ones, which the
      // vector form leaves to the lane-by-lane one.
      std::vector<double> rate(1 + rng() % 40);
      for (double& r : rate) r = rng() % 4 == 0 ? std::floor(real(rng)) + 0.5 : real(rng);
      if (variant == 2) {
        rate[0] = -2.25;
        if (rate.size() > 1) rate[1] = 0x1p62;
      }
      const double fallback = variant == 1 ? 0.5 : real(rng);
      const std::uint64_t l1_latency = variant == 1 ? 0 : 1 + rng() % 40;
      std::vector<std::uint32_t> rank(count), nodes(count);
      std::vector<std::uint64_t> start(count);
      for (std::size_t i = 0; i < count; ++i) {
        rank[i] = static_cast<std::uint32_t>(rng() % (rate.size() + 3));  // some past the rates
        nodes[i] = static_cast<std::uint32_t>(rng() % 5 == 0 ? 0 : rng() % 300);
        start[i] = rng() % 100000;
      }
      std::vector<std::uint64_t> want(count);
      for (std::size_t i = 0; i < count; ++i) {
        const double r = rank[i] < rate.size() ? rate[rank[i]] : fallback;
        want[i] = l1_latency * nodes[i] + static_cast<std::uint64_t>(std::llround(r * nodes[i]));
      }
      std::vector<std::uint64_t> scalar = start, dispatched = start, lanes = start;
      WriteBorrowedCyclesScalar(rank.data(), nodes.data(), count, rate.data(), rate.size(), fallback, l1_latency,
                                scalar.data());
      WriteBorrowedCycles(rank.data(), nodes.data(), count, rate.data(), rate.size(), fallback, l1_latency,
                          dispatched.data());
      EXPECT_EQ(scalar, want) << count << " lanes, variant " << variant;
      EXPECT_EQ(dispatched, want) << count << " lanes, variant " << variant;
      if (CpuHasAvx512()) {
        WriteBorrowedCyclesLanes(rank.data(), nodes.data(), count, rate.data(), rate.size(), fallback, l1_latency,
                                 lanes.data());
        EXPECT_EQ(lanes, want) << count << " lanes, variant " << variant;
      }
    }
  }
  if (!CpuHasAvx512()) GTEST_SKIP() << "this host has no AVX-512: the lane-by-lane form was checked";
}

}  // namespace
}  // namespace rc
