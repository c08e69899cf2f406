#pragma once
// OBB queries against a flattened box tree: "does this OBB overlap the
// union of the scene's boxes" (touching counts), one SACT per visited
// node, with every fetch and test recorded for the backends.
//
// Pricing a batch on the backends (DESIGN.md, "run once, price many
// times"): a CollisionBatch maps one-to-one onto a KernelRecord for the
// shipped program programs/sact_obb_aabb.asm (StepProgramKind::kSactTest;
// sact_kernel_record.h builds it, and the RoboCore API's CheckCollisions
// returns it):
//   region   {base_address, node_bytes, tree node count}
//   query i  its visits in order: address = Address(visit), node exit =
//            visit.exit (0..14: RETURN_IF #k, the axis that separated) or
//            kNoExit (0xFF) for an overlap (the program's PUSH path).
// Visits decided by a sphere pre-test (decided_by != kAxes) ran no SACT
// stage; the shipped program has no sphere section, so they cannot be
// priced by it (the CLI keeps pre-tests off unless asked).
#include <cstdint>
#include <vector>

#include "robocore/collision/box_tree_traversal.h"
#include "robocore/collision/obb.h"

namespace rc {

// Where the node array sits in the modelled device memory (as robocore's
// DeviceLayout: away from 0 so a bad address stands out).
inline constexpr std::uint64_t kDefaultTreeBase = std::uint64_t{1} << 32;  // bytes

template <typename Scalar>
struct CollisionOptions {
  SactOptions<Scalar> sact;
  TraversalOrder order = TraversalOrder::kDepthFirst;
};

template <typename Scalar>
TraversalOutcome CollideObb(const FlatBoxTree<Scalar>& tree, const Obb<Scalar>& obb,
                            const CollisionOptions<Scalar>& options, std::vector<NodeVisit>* visits = nullptr);
// The same with a reusable pending list (box_tree_traversal.h), for a caller
// that runs many queries.
template <typename Scalar>
TraversalOutcome CollideObb(const FlatBoxTree<Scalar>& tree, const Obb<Scalar>& obb,
                            const CollisionOptions<Scalar>& options, std::vector<NodeVisit>* visits,
                            std::vector<std::uint32_t>* scratch);

// The same, calling on_visit(const NodeVisit&) with each visit in order
// instead of keeping them (VisitBoxTree): how a recorder keeps each fetch's
// exit and address without a list of visits. CollideObb is this with a
// visitor that appends to `visits`.
template <typename Scalar, typename OnVisit>
TraversalOutcome CollideObbVisiting(const FlatBoxTree<Scalar>& tree, const Obb<Scalar>& obb,
                                    const CollisionOptions<Scalar>& options, OnVisit&& on_visit,
                                    std::vector<std::uint32_t>* scratch) {
  const SactPreparedObb<Scalar> prepared = PrepareSactObb(obb, options.sact);
  auto sact = [&prepared](const FlatNode<Scalar>& node) {
    const SactResult r = TestPreparedObbAabb(prepared, node.box());
    NodeVisit v;
    v.exit = r.separating_axis;
    v.axes_tested = r.axes_tested;
    v.decided_by = r.decided_by;
    return v;
  };
  return VisitBoxTree(tree, options.order, sact, on_visit, scratch);
}

// Tests every box in order until one overlaps: what the tree must equal.
template <typename Scalar>
bool CollidesBruteForce(const std::vector<Aabb<Scalar>>& boxes, const Obb<Scalar>& obb,
                        const SactOptions<Scalar>& options);

// What each query of a batch is: a robot-link OBB (the SACT per node) or
// one sphere of the sphere robot (sphere_robot.h; one sphere test per node).
enum class CollisionRobotModel : std::uint8_t { kObb, kSpheres };

// A recorded batch. Memory: 8 bytes per visit + 16 per query.
struct CollisionBatch {
  CollisionRobotModel robot_model = CollisionRobotModel::kObb;
  std::vector<TraversalOutcome> outcomes;       // one per query, in input order
  std::vector<std::uint64_t> visit_offsets{0};  // CSR: query i's visits are [offsets[i], offsets[i+1])
  std::vector<NodeVisit> visits;
  std::uint64_t base_address = kDefaultTreeBase;  // bytes
  std::uint32_t node_bytes = 0;                   // bytes per node fetch
  std::uint8_t scalar_bytes = 8;                  // sizeof(Scalar) of the kernel that ran
  std::uint64_t node_count = 0;                   // nodes in the array
  bool sphere_pretests = false;

  std::size_t query_count() const { return outcomes.size(); }
  std::uint64_t Address(const NodeVisit& v) const { return base_address + std::uint64_t{v.node} * node_bytes; }
};

template <typename Scalar>
CollisionBatch CollideBatch(const FlatBoxTree<Scalar>& tree, const std::vector<Obb<Scalar>>& obbs,
                            const CollisionOptions<Scalar>& options, std::uint64_t base_address = kDefaultTreeBase);

// Each OBB's outcome, in input order, without keeping any visit: for a
// caller that needs the answers only (a comparison), at none of a batch's
// memory.
template <typename Scalar>
std::vector<TraversalOutcome> CollideAnswers(const FlatBoxTree<Scalar>& tree, const std::vector<Obb<Scalar>>& obbs,
                                             const CollisionOptions<Scalar>& options);

// The same into `batch`, whose contents are replaced and whose buffers are
// reused: a caller that launches many batches (a configuration space)
// allocates and page-faults its visit buffer once instead of per launch.
template <typename Scalar>
void CollideBatchInto(const FlatBoxTree<Scalar>& tree, const std::vector<Obb<Scalar>>& obbs,
                      const CollisionOptions<Scalar>& options, CollisionBatch* batch,
                      std::uint64_t base_address = kDefaultTreeBase);

}  // namespace rc
