#include "backends/scheduler/crossover_threshold.h"

#include <algorithm>
#include <limits>

namespace rc {

KernelRecord MakeUniformProbe(const KernelRecord& t, std::size_t queries, std::uint32_t nodes,
                              const AddressSample& sample) {
  return MakeProbe(t, std::vector<std::uint32_t>(queries, nodes), sample);
}

KernelRecord MakeSpreadProbe(const KernelRecord& t, std::size_t queries, std::uint32_t max_nodes,
                             const AddressSample& sample) {
  // Query q fetches 1 + (q * 37) mod max_nodes nodes: every length in
  // [1, max_nodes] equally often, neighbours in a warp far apart.
  std::vector<std::uint32_t> nodes(queries);
  const std::uint32_t top = std::max<std::uint32_t>(1, max_nodes);
  for (std::size_t q = 0; q < queries; ++q) nodes[q] = 1 + static_cast<std::uint32_t>((q * 37) % top);
  return MakeProbe(t, nodes, sample);
}

KernelRecord MakeProbe(const KernelRecord& t, const std::vector<std::uint32_t>& nodes_per_query,
                       const AddressSample& sample) {
  const std::size_t queries = nodes_per_query.size();
  KernelRecord probe;
  probe.step_kind = t.step_kind;
  probe.leaf_kind = t.leaf_kind;
  probe.program = t.program;
  probe.leaf = t.leaf;
  probe.regions = t.regions;
  probe.node_bytes = t.node_bytes;
  probe.scalar_bytes = t.scalar_bytes;
  const MemoryRegion& region = t.regions.at(0);
  const std::uint64_t elements = region.elements > 0 ? region.elements : 1;
  probe.address_sample = sample;
  probe.fetch_offsets.resize(queries + 1);
  probe.last_exits.resize(queries);
  // Queries start spread over the structure (a large odd stride) and walk
  // consecutive elements, like rays crossing cells of one row.
  constexpr std::uint64_t kStartStride = 7919;
  for (std::size_t q = 0; q < queries; ++q) {
    const std::uint32_t nodes = nodes_per_query[q];
    probe.last_exits[q] = nodes > 0 ? kRayHitReturn : kNoExit;
    probe.fetch_offsets[q + 1] = probe.fetch_offsets[q] + nodes;
    if (sample.KeepsQuery(q))
      for (std::uint32_t j = 0; j < nodes; ++j) {
        const std::uint64_t element = (q * kStartStride + j) % elements;
        probe.fetch_addresses.push_back(region.base + element * region.element_bytes);
      }
  }
  if (!sample.KeepsAll()) probe.address_offsets = KeptAddressOffsets(probe.fetch_offsets, sample);
  return probe;
}

CrossoverResult DeriveCrossoverThreshold(const Backend& high, const Backend& low, const KernelRecord& t,
                                         std::size_t queries, std::uint32_t max_nodes, const AddressSample& sample) {
  CrossoverResult result;
  // advantage(n) > 0 when the high backend is cheaper at n nodes per query.
  auto advantage = [&](std::uint32_t n) {
    const KernelRecord probe = MakeUniformProbe(t, queries, n, sample);
    ++result.probes_priced;
    return static_cast<double>(low.Price(probe).cycles) - static_cast<double>(high.Price(probe).cycles);
  };
  if (advantage(1) > 0.0) {
    result.threshold_nodes_per_query = 0.0;
    return result;
  }
  if (!(advantage(max_nodes) > 0.0)) {
    result.threshold_nodes_per_query = std::numeric_limits<double>::infinity();
    return result;
  }
  std::uint32_t lo = 1, hi = max_nodes;  // advantage(lo) <= 0 < advantage(hi)
  while (hi - lo > 1) {
    const std::uint32_t mid = lo + (hi - lo) / 2;
    (advantage(mid) > 0.0 ? hi : lo) = mid;
  }
  // The adaptive policy picks high when nodes per query > threshold, so the
  // threshold is the largest n at which low is still at least as cheap.
  result.threshold_nodes_per_query = lo;
  result.has_crossing = true;
  return result;
}

}  // namespace rc
