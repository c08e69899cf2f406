#include "robocore/collision/tree_collision.h"

#include <stdexcept>

namespace rc {

const char* ToString(TraversalOrder order) { return order == TraversalOrder::kDepthFirst ? "dfs" : "bfs"; }

TraversalOrder ParseTraversalOrder(const std::string& name) {
  if (name == "dfs") return TraversalOrder::kDepthFirst;
  if (name == "bfs") return TraversalOrder::kBreadthFirst;
  throw std::invalid_argument("traversal order '" + name + "': expected dfs or bfs");
}

template <typename Scalar>
TraversalOutcome CollideObb(const FlatBoxTree<Scalar>& tree, const Obb<Scalar>& obb,
                            const CollisionOptions<Scalar>& options, std::vector<NodeVisit>* visits) {
  return CollideObbVisiting(tree, obb, options, AppendVisitsTo(visits), nullptr);
}

template <typename Scalar>
TraversalOutcome CollideObb(const FlatBoxTree<Scalar>& tree, const Obb<Scalar>& obb,
                            const CollisionOptions<Scalar>& options, std::vector<NodeVisit>* visits,
                            std::vector<std::uint32_t>* scratch) {
  return CollideObbVisiting(tree, obb, options, AppendVisitsTo(visits), scratch);
}

template <typename Scalar>
bool CollidesBruteForce(const std::vector<Aabb<Scalar>>& boxes, const Obb<Scalar>& obb,
                        const SactOptions<Scalar>& options) {
  for (const Aabb<Scalar>& box : boxes)
    if (TestObbAabb(obb, box, options).overlaps()) return true;
  return false;
}

template <typename Scalar>
void CollideBatchInto(const FlatBoxTree<Scalar>& tree, const std::vector<Obb<Scalar>>& obbs,
                      const CollisionOptions<Scalar>& options, CollisionBatch* batch, std::uint64_t base_address) {
  std::string error;
  if (!options.sact.IsValid(&error)) throw std::invalid_argument("SACT options: " + error);
  batch->robot_model = CollisionRobotModel::kObb;
  batch->base_address = base_address;
  batch->node_bytes = tree.node_bytes();
  batch->scalar_bytes = sizeof(Scalar);
  batch->node_count = tree.nodes().size();
  batch->sphere_pretests = options.sact.sphere_pretests;
  batch->outcomes.clear();
  batch->outcomes.reserve(obbs.size());
  batch->visit_offsets.assign(1, 0);
  batch->visit_offsets.reserve(obbs.size() + 1);
  batch->visits.clear();
  std::vector<std::uint32_t> scratch;
  for (const Obb<Scalar>& obb : obbs) {
    batch->outcomes.push_back(CollideObbVisiting(tree, obb, options, AppendVisitsTo(&batch->visits), &scratch));
    batch->visit_offsets.push_back(batch->visits.size());
  }
}

template <typename Scalar>
CollisionBatch CollideBatch(const FlatBoxTree<Scalar>& tree, const std::vector<Obb<Scalar>>& obbs,
                            const CollisionOptions<Scalar>& options, std::uint64_t base_address) {
  CollisionBatch batch;
  CollideBatchInto(tree, obbs, options, &batch, base_address);
  return batch;
}

template <typename Scalar>
std::vector<TraversalOutcome> CollideAnswers(const FlatBoxTree<Scalar>& tree, const std::vector<Obb<Scalar>>& obbs,
                                             const CollisionOptions<Scalar>& options) {
  std::vector<TraversalOutcome> out;
  out.reserve(obbs.size());
  std::vector<std::uint32_t> pending;
  for (const Obb<Scalar>& obb : obbs) out.push_back(CollideObb(tree, obb, options, nullptr, &pending));
  return out;
}

#define RC_INSTANTIATE(Scalar)                                                                                        \
  template TraversalOutcome CollideObb(const FlatBoxTree<Scalar>&, const Obb<Scalar>&,                                \
                                       const CollisionOptions<Scalar>&, std::vector<NodeVisit>*);                     \
  template TraversalOutcome CollideObb(const FlatBoxTree<Scalar>&, const Obb<Scalar>&,                                \
                                       const CollisionOptions<Scalar>&, std::vector<NodeVisit>*,                      \
                                       std::vector<std::uint32_t>*);                                                  \
  template bool CollidesBruteForce(const std::vector<Aabb<Scalar>>&, const Obb<Scalar>&, const SactOptions<Scalar>&); \
  template CollisionBatch CollideBatch(const FlatBoxTree<Scalar>&, const std::vector<Obb<Scalar>>&,                   \
                                       const CollisionOptions<Scalar>&, std::uint64_t);                               \
  template void CollideBatchInto(const FlatBoxTree<Scalar>&, const std::vector<Obb<Scalar>>&,                         \
                                 const CollisionOptions<Scalar>&, CollisionBatch*, std::uint64_t);                    \
  template std::vector<TraversalOutcome> CollideAnswers(const FlatBoxTree<Scalar>&, const std::vector<Obb<Scalar>>&,  \
                                                        const CollisionOptions<Scalar>&);
RC_INSTANTIATE(float)
RC_INSTANTIATE(double)
#undef RC_INSTANTIATE

}  // namespace rc
