#pragma once
// The traversal every query of a flattened box tree runs: visit a node,
// test its box, descend into the children of a box that overlaps, stop at
// the first leaf that overlaps (early exit, as the artifact's kernel).
// Each visit is one node fetch and one node test, recorded in order, so a
// backend can price the fetches (address = base + index x node bytes) and
// the tests (NodeVisit: SACT exit axis and axes tested).
//
// Depth-first (a stack; children in order, first child first) reaches a
// colliding leaf after about one root-to-leaf path and keeps the pending
// list short. Breadth-first (a queue) is what the artifact does. Both give
// the same answer; a collision-free query visits exactly the same nodes
// either way (a node is visited iff all its ancestors overlap); they differ
// only in how many nodes a colliding query visits before its first hit.
#include <cstdint>
#include <string>
#include <vector>

#include "robocore/collision/flat_box_tree.h"
#include "robocore/collision/sact.h"

namespace rc {

enum class TraversalOrder : std::uint8_t { kDepthFirst, kBreadthFirst };
const char* ToString(TraversalOrder order);
// "dfs" | "bfs"; throws std::invalid_argument otherwise.
TraversalOrder ParseTraversalOrder(const std::string& name);

// "No node was tested" (an empty scene).
inline constexpr std::int8_t kNoNodeTested = -3;

// One node fetch and its test.
struct NodeVisit {
  std::uint32_t node = 0;           // index in the flat node array
  std::int8_t exit = kSactOverlap;  // 0..14, kSactOverlap or kSactSphereSeparated
  std::uint8_t axes_tested = 0;     // SACT axes the test ran (0..15)
  SactDecision decided_by = SactDecision::kAxes;
  bool overlaps() const { return exit == kSactOverlap; }
};

struct TraversalOutcome {
  bool collides = false;
  std::uint32_t colliding_box = kNoBox;  // scene box index of the leaf that ended the query
  std::uint32_t nodes_visited = 0;
  std::int8_t last_exit = kNoNodeTested;  // exit of the query's last node test
};

// NodeTest: NodeVisit(const FlatNode<Scalar>&), filling exit, axes_tested
// and decided_by. OnVisit: void(const NodeVisit&), called with each visit
// in order (node set), so a recorder keeps what it needs without a list of
// visits. `scratch`, if given, holds the pending nodes (its contents are
// replaced), so a caller running many queries allocates the list once.
template <typename Scalar, typename NodeTest, typename OnVisit>
TraversalOutcome VisitBoxTree(const FlatBoxTree<Scalar>& tree, TraversalOrder order, NodeTest&& test,
                              OnVisit&& on_visit, std::vector<std::uint32_t>* scratch = nullptr) {
  TraversalOutcome out;
  const auto& nodes = tree.nodes();
  if (nodes.empty()) return out;
  std::vector<std::uint32_t> local;
  // A stack (depth-first) or a queue from `head` (breadth-first).
  std::vector<std::uint32_t>& pending = scratch ? *scratch : local;
  pending.assign(1, 0);
  std::size_t head = 0;
  const bool depth_first = order == TraversalOrder::kDepthFirst;
  while (depth_first ? !pending.empty() : head < pending.size()) {
    std::uint32_t index;
    if (depth_first) {
      index = pending.back();
      pending.pop_back();
    } else {
      index = pending[head++];
    }
    const FlatNode<Scalar>& node = nodes[index];
    NodeVisit visit = test(node);
    visit.node = index;
    ++out.nodes_visited;
    out.last_exit = visit.exit;
    on_visit(static_cast<const NodeVisit&>(visit));
    if (!visit.overlaps()) continue;
    if (node.is_leaf()) {
      out.collides = true;
      out.colliding_box = node.first_child;
      return out;
    }
    if (depth_first) {
      for (std::uint32_t c = node.first_child + node.child_count; c-- > node.first_child;) pending.push_back(c);
    } else {
      for (std::uint32_t c = node.first_child; c < node.first_child + node.child_count; ++c) pending.push_back(c);
    }
  }
  return out;
}

// A visitor that appends each visit to `visits` (none when null).
inline auto AppendVisitsTo(std::vector<NodeVisit>* visits) {
  return [visits](const NodeVisit& v) {
    if (visits) visits->push_back(v);
  };
}

// VisitBoxTree with `visits`, if given, getting this query's visits appended.
template <typename Scalar, typename NodeTest>
TraversalOutcome TraverseBoxTree(const FlatBoxTree<Scalar>& tree, TraversalOrder order, NodeTest&& test,
                                 std::vector<NodeVisit>* visits, std::vector<std::uint32_t>* scratch = nullptr) {
  return VisitBoxTree(tree, order, test, AppendVisitsTo(visits), scratch);
}

}  // namespace rc
