#pragma once
// What a recorded collision batch did, in the numbers a study or the
// adaptive scheduler reads: collisions, nodes visited per query (mean and
// a power-of-two histogram), how node tests ended (exit-axis distribution)
// and the SACT stages they executed (the work a cost model prices).
#include <array>
#include <cstdint>
#include <vector>

#include "robocore/collision/tree_collision.h"

namespace rc {

// Exit codes -3..14 (kNoNodeTested, kSactSphereSeparated, kSactOverlap,
// axes 0..14) as array slots 0..17.
inline constexpr int kExitSlots = kSactAxisCount + 3;
inline constexpr int ExitSlot(int exit) { return exit + 3; }
inline constexpr int ExitOfSlot(int slot) { return slot - 3; }

struct NodesHistogramBin {
  std::uint32_t lo = 0, hi = 0;  // nodes visited, inclusive: 0, 1, 2-3, 4-7, ...
  std::uint64_t queries = 0;
};

struct CollisionSummary {
  std::uint64_t queries = 0;
  std::uint64_t collisions = 0;
  std::uint64_t node_visits = 0;
  std::uint32_t nodes_max = 0;
  double nodes_per_query_mean = 0;
  std::vector<NodesHistogramBin> nodes_histogram;
  std::array<std::uint64_t, kExitSlots> node_test_exits{};   // over all node tests
  std::array<std::uint64_t, kExitSlots> query_last_exits{};  // the last test of each query
  // SACT stages executed over the batch.
  std::uint64_t sphere_pretests = 0;
  std::uint64_t pre_process = 0;
  std::uint64_t box_normal = 0;
  std::uint64_t edge_edge = 0;
  std::uint64_t sphere_decided = 0;  // node tests a sphere pre-test decided (no SACT)
};

CollisionSummary Summarize(const CollisionBatch& batch);

}  // namespace rc
