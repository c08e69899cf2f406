#pragma once
// The adaptive scheduler's threshold, derived from the backends' own cost
// models rather than tuned: the nodes per query at which the traversal unit
// (high) becomes cheaper than the CUDA cores (low) for a batch like the
// workload's.
//
// Probe: a synthetic batch with the template record's program, leaf, memory
// regions and query count, in which every query fetches n nodes at
// consecutive addresses (a ray crossing n cells of one row) and stops at the
// last. Both backends price the probe for a given n; the threshold is the
// smallest n at which high is cheaper than low. The probe's cost difference
// is searched by bisection, which assumes one crossing in [1, max_nodes]
// (checked at both ends). Without a crossing the threshold is 0 (high always
// cheaper) or +inf (low always cheaper), and the adaptive policy degenerates
// to a static one, which the summary then says.
#include <cstdint>
#include <vector>

#include "backends/backend.h"
#include "robocore/kernel_record.h"
#include "robocore/section_timing.h"

namespace rc {

// The bound on the nodes one query fetches when the workload knows none:
// the threshold's search range and the spread probe's longest query.
inline constexpr std::uint32_t kDefaultMaxNodesPerQuery = 1024;

// A probe record: `queries` queries of `nodes` fetches each, with the
// template's program, leaf, regions and node size; addresses kept for the
// queries `sample` keeps.
KernelRecord MakeUniformProbe(const KernelRecord& template_record, std::size_t queries, std::uint32_t nodes,
                              const AddressSample& sample = {});
// The same with every length from 1 to max_nodes equally often, interleaved
// so that a warp's queries diverge: what a batch of rays from poses spread
// over the map looks like before anything has been measured.
KernelRecord MakeSpreadProbe(const KernelRecord& template_record, std::size_t queries, std::uint32_t max_nodes,
                             const AddressSample& sample = {});
// One query per entry of nodes_per_query, fetching that many nodes.
KernelRecord MakeProbe(const KernelRecord& template_record, const std::vector<std::uint32_t>& nodes_per_query,
                       const AddressSample& sample = {});

struct CrossoverResult {
  double threshold_nodes_per_query = 0.0;  // 0 or +inf when there is no crossing
  bool has_crossing = false;
  int probes_priced = 0;
};

// max_nodes: the most nodes a query of the workload can fetch (the search's
// upper end). The probes keep the addresses `sample` keeps (the ledger's
// replay sample), so a sampled ledger prices them as cheaply as its batches.
CrossoverResult DeriveCrossoverThreshold(const Backend& high, const Backend& low, const KernelRecord& template_record,
                                         std::size_t queries, std::uint32_t max_nodes = kDefaultMaxNodesPerQuery,
                                         const AddressSample& sample = {});

}  // namespace rc
