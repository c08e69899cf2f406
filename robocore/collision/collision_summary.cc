#include "robocore/collision/collision_summary.h"

#include <algorithm>

namespace rc {
namespace {

// Bin 0 holds 0 nodes; bin b >= 1 holds [2^(b-1), 2^b - 1].
std::size_t BinOf(std::uint32_t nodes) {
  std::size_t b = 0;
  while (nodes > 0) nodes >>= 1, ++b;
  return b;
}

}  // namespace

CollisionSummary Summarize(const CollisionBatch& batch) {
  CollisionSummary s;
  s.queries = batch.query_count();
  for (const TraversalOutcome& q : batch.outcomes) {
    s.collisions += q.collides;
    s.node_visits += q.nodes_visited;
    s.nodes_max = std::max(s.nodes_max, q.nodes_visited);
    ++s.query_last_exits[ExitSlot(q.last_exit)];
  }
  s.nodes_per_query_mean = s.queries ? double(s.node_visits) / double(s.queries) : 0.0;
  s.nodes_histogram.resize(BinOf(s.nodes_max) + 1);
  for (std::size_t b = 0; b < s.nodes_histogram.size(); ++b) {
    s.nodes_histogram[b].lo = b == 0 ? 0 : 1u << (b - 1);
    s.nodes_histogram[b].hi = b == 0 ? 0 : (1u << (b - 1)) * 2 - 1;
  }
  for (const TraversalOutcome& q : batch.outcomes) ++s.nodes_histogram[BinOf(q.nodes_visited)].queries;
  for (const NodeVisit& v : batch.visits) {
    ++s.node_test_exits[ExitSlot(v.exit)];
    SactResult r;
    r.separating_axis = v.exit;
    r.axes_tested = v.axes_tested;
    r.decided_by = v.decided_by;
    const SactStageCounts c = StagesOf(r, batch.sphere_pretests);
    s.sphere_pretests += c.sphere_pretests;
    s.pre_process += c.pre_process;
    s.box_normal += c.box_normal;
    s.edge_edge += c.edge_edge;
    s.sphere_decided += v.decided_by != SactDecision::kAxes;
  }
  return s;
}

}  // namespace rc
