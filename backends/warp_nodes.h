#pragma once
// Per warp of a record (warp_size consecutive queries, the last warp perhaps
// partial): its steps, the most nodes any of its lanes fetched (a warp
// steps until its longest lane ends), and its lanes' nodes in all. Read from
// the record's fetch_offsets (queries + 1 prefix sums), which every cost
// model walks warp by warp.
//
// Integer maxima and sums: the AVX-512 form (where the host has it) and the
// one-query-at-a-time loop give the same numbers
// (tests/backends/warp_nodes_test.cc).
#include <cstddef>
#include <cstdint>
#include <vector>

namespace rc {

// Writes steps[w] and lane_nodes[w] for every warp w < ceil(queries /
// warp_size) (warp_size >= 1). A query's node count fits 32 bits
// (RayHit::nodes), so a warp's steps do.
void CountWarpNodes(const std::uint64_t* fetch_offsets, std::size_t queries, std::size_t warp_size,
                    std::uint32_t* steps, std::uint64_t* lane_nodes);

// The same, one query at a time; and in AVX-512 lanes, only where the host
// has them (CpuHasAvx512(), common/cpu_features.h). CountWarpNodes takes
// the AVX-512 form where it is in use (UseAvx512()).
void CountWarpNodesScalar(const std::uint64_t* fetch_offsets, std::size_t queries, std::size_t warp_size,
                          std::uint32_t* steps, std::uint64_t* lane_nodes);
void CountWarpNodesLanes(const std::uint64_t* fetch_offsets, std::size_t queries, std::size_t warp_size,
                         std::uint32_t* steps, std::uint64_t* lane_nodes);

// Both counts of every warp, for a whole record's fetch_offsets (queries +
// 1 entries): what the memory replay and the SIMT model both read, counted
// once per record and warp size (PricingContext::WarpNodes).
struct WarpNodeCounts {
  std::vector<std::uint32_t> steps;
  std::vector<std::uint64_t> lane_nodes;
};
WarpNodeCounts CountWarpNodes(const std::vector<std::uint64_t>& fetch_offsets, std::size_t warp_size);

}  // namespace rc
