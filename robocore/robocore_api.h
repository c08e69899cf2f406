#pragma once
// The RoboCore programming API of the RoboGPU paper, as a thin facade over
// the micro-op programs (micro_program.h), the recorded ray batch
// (ray_batch_recorded.h) and the collision kernel (collision/):
//
//   ConfigRoboCore(program)   the intersection program every unit runs
//   ConfigDecode(layouts)     how the fetch unit decodes the nodes it loads
//   CheckCollisions(obbs, tree, results)
//                             robot-link OBBs against a flattened box tree
//                             (programs/sact_obb_aabb.asm, one SACT per
//                             visited node); per-OBB results and the kernel
//                             record a backend prices
//   ExecuteRoboCore(queries, scene, results)
//                             runs a ray batch; returns the functional
//                             results and the kernel record a backend prices
//
// Timing is not here: it belongs to the backends (backends/backend.h),
// which price the record this facade produces. That keeps "run once, price
// many times": one ExecuteRoboCore, then RoboCore, TTA+ and SIMT costs.
#include <memory>
#include <vector>

#include "robocore/collision/tree_collision.h"
#include "robocore/kernel_record.h"
#include "robocore/ray_batch_recorded.h"

namespace rc {

// What the fetch unit reads for one kind of node.
struct NodeLayout {
  FetchKind kind = FetchKind::kGridCell;
  std::uint32_t element_bytes = 1;  // bytes of one node
};

// What CheckCollisions returns for one OBB (the CLI's output row).
struct CollisionResult {
  bool collides = false;
  std::uint32_t nodes_visited = 0;
  // How the OBB's last node test ended: 0..14 the SACT axis that separated
  // (a collision-free OBB), kSactOverlap (-1, the colliding leaf), or
  // kNoNodeTested (-3, an empty tree).
  std::int8_t exit_axis = kNoNodeTested;
  std::uint32_t colliding_box = kNoBox;  // scene box index, kNoBox when free
};

// A traversal's outcome as CheckCollisions reports it.
inline CollisionResult ResultOf(const TraversalOutcome& q) {
  return CollisionResult{q.collides, q.nodes_visited, q.last_exit, q.colliding_box};
}

class RoboCoreContext {
 public:
  // A ray program keeps the ray-cast exit contract (kernel_record.h: loop
  // RETURN_IF #0 hit, #1 end); a collision program keeps the SACT exit
  // contract (collision/sact_kernel_record.h: PRE, then RETURN_IF #k after
  // the test of axis k). Throws std::invalid_argument if the program has no
  // loop, has fewer than two loop RETURN_IFs, holds SACT micro-ops without
  // keeping the SACT contract, or if `leaf` holds anything but an epilogue.
  void ConfigRoboCore(std::shared_ptr<const MicroProgram> program, std::shared_ptr<const MicroProgram> leaf = nullptr);
  // One layout per node kind the program may load; replaces earlier ones.
  void ConfigDecode(std::vector<NodeLayout> layouts);

  // Runs the batch on the host kernels, recording every node fetch. Without
  // ConfigRoboCore, the shipped program for the scene's method and the
  // beam-model leaf are used. Throws std::invalid_argument if ConfigDecode
  // was called and has no layout for the scene's node kind, or one whose
  // size disagrees with the structure in memory.
  // Also throws if the configured program holds SACT micro-ops (a
  // collision program).
  void ExecuteRoboCore(const RayBatch& queries, const RayCastScene& scene, std::vector<RayHit>& results,
                       KernelRecord& record) const;

  // Runs every OBB against the tree (CollideBatch: the staged SACT at every
  // visited node, early exit at the first colliding leaf) and fills one
  // result per OBB, in input order, and the batch's kernel record
  // (SactKernelRecord with the configured program). Without
  // ConfigRoboCore, the shipped SACT program is used. Throws
  // std::invalid_argument if the configured program keeps no SACT exit
  // contract (a ray program), if ConfigDecode was called and has no
  // FetchKind::kTreeNode layout or one whose size is not the tree's node
  // size, if the options are invalid, or if they ask for sphere pre-tests
  // (the SACT program has no section for them). With `visits` set, it also
  // receives the batch the kernel ran (every visit's node, SACT stages and
  // exit, which the record does not keep), so that a caller summarising the
  // visits does not run the kernel again.
  template <typename Scalar>
  void CheckCollisions(const std::vector<Obb<Scalar>>& obbs, const FlatBoxTree<Scalar>& tree,
                       std::vector<CollisionResult>& results, KernelRecord& record,
                       const CollisionOptions<Scalar>& options = {}, CollisionBatch* visits = nullptr) const;

 private:
  std::shared_ptr<const MicroProgram> program_;
  std::shared_ptr<const MicroProgram> leaf_;
  bool leaf_configured_ = false;
  std::vector<NodeLayout> layouts_;

  // The layout ConfigDecode gave for `region`'s node kind; throws if none
  // or if its size disagrees. Does nothing without ConfigDecode.
  void CheckLayout(const MemoryRegion& region) const;
};

}  // namespace rc
