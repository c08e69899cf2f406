// Per-warp steps and lane nodes (warp_nodes.h): every form against the
// definition, at warp sizes that leave the lanes' last step part full and
// with a partial last warp.
#include "backends/warp_nodes.h"

#include <algorithm>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "common/cpu_features.h"

namespace rc {
namespace {

TEST(WarpNodes, EveryFormGivesEachWarpsLongestLaneAndItsNodes) {
  std::mt19937_64 rng(3);
  for (std::size_t queries : {0, 1, 31, 32, 33, 1000}) {
    // Node counts with many zeros and some near the 32-bit limit.
    std::vector<std::uint64_t> offsets{0};
    std::vector<std::uint64_t> nodes;
    for (std::size_t q = 0; q < queries; ++q) {
      const std::uint64_t k = rng() % 5 == 0 ? 0 : rng() % 50 == 0 ? 0xFFFFFFF0u + rng() % 15 : rng() % 300;
      nodes.push_back(k);
      offsets.push_back(offsets.back() + k);
    }
    for (std::size_t warp_size : {1, 7, 8, 13, 32, 64}) {
      const std::size_t warps = (queries + warp_size - 1) / warp_size;
      std::vector<std::uint32_t> want_steps(warps);
      std::vector<std::uint64_t> want_nodes(warps);
      for (std::size_t w = 0; w < warps; ++w) {
        const std::size_t lo = w * warp_size, hi = std::min(queries, lo + warp_size);
        want_steps[w] = static_cast<std::uint32_t>(*std::max_element(nodes.begin() + lo, nodes.begin() + hi));
        for (std::size_t q = lo; q < hi; ++q) want_nodes[w] += nodes[q];
      }
      std::vector<std::uint32_t> steps(warps, 7);
      std::vector<std::uint64_t> lane_nodes(warps, 7);
      CountWarpNodesScalar(offsets.data(), queries, warp_size, steps.data(), lane_nodes.data());
      EXPECT_EQ(steps, want_steps) << queries << " queries, warps of " << warp_size;
      EXPECT_EQ(lane_nodes, want_nodes) << queries << " queries, warps of " << warp_size;
      steps.assign(warps, 7);
      lane_nodes.assign(warps, 7);
      CountWarpNodes(offsets.data(), queries, warp_size, steps.data(), lane_nodes.data());
      EXPECT_EQ(steps, want_steps) << queries << " queries, warps of " << warp_size;
      EXPECT_EQ(lane_nodes, want_nodes) << queries << " queries, warps of " << warp_size;
      if (CpuHasAvx512()) {
        steps.assign(warps, 7);
        lane_nodes.assign(warps, 7);
        CountWarpNodesLanes(offsets.data(), queries, warp_size, steps.data(), lane_nodes.data());
        EXPECT_EQ(steps, want_steps) << queries << " queries, warps of " << warp_size;
        EXPECT_EQ(lane_nodes, want_nodes) << queries << " queries, warps of " << warp_size;
      }
    }
  }
  if (!CpuHasAvx512()) GTEST_SKIP() << "this host has no AVX-512: the one-query-at-a-time form was checked";
}

TEST(WarpNodes, AWarpSizeOfZeroIsRefused) {
  const std::uint64_t offsets[] = {0, 1};
  std::uint32_t steps = 0;
  std::uint64_t lane_nodes = 0;
  EXPECT_THROW(CountWarpNodes(offsets, 1, 0, &steps, &lane_nodes), std::invalid_argument);
}

}  // namespace
}  // namespace rc
