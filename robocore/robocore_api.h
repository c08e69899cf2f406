#pragma once
// The RoboCore programming API of the RoboGPU paper, as a thin facade over
// the micro-op programs (micro_program.h) and the recorded batch
// (ray_batch_recorded.h):
//
//   ConfigRoboCore(program)   the intersection program every unit runs
//   ConfigDecode(layouts)     how the fetch unit decodes the nodes it loads
//   ExecuteRoboCore(queries, scene, results)
//                             runs a batch; returns the functional results
//                             and the kernel record a backend prices
//
// The paper's fourth call, CheckCollisions(robot OBBs, scene tree,
// results), belongs to the collision kernel (a later issue). It fits this
// facade unchanged: ConfigRoboCore takes programs/sact_obb_aabb.asm,
// ConfigDecode takes the flattened octree node layout, and CheckCollisions
// fills the same KernelRecord (one node fetch and one SACT exit axis per
// visited node), so every backend prices it without new interfaces.
//
// Timing is not here: it belongs to the backends (backends/backend.h),
// which price the record this facade produces. That keeps "run once, price
// many times": one ExecuteRoboCore, then RoboCore, TTA+ and SIMT costs.
#include <memory>
#include <vector>

#include "robocore/kernel_record.h"
#include "robocore/ray_batch_recorded.h"

namespace rc {

// What the fetch unit reads for one kind of node.
struct NodeLayout {
  FetchKind kind = FetchKind::kGridCell;
  std::uint32_t element_bytes = 1;  // bytes of one node
};

class RoboCoreContext {
 public:
  // Throws std::invalid_argument if the program has no loop, or fewer than
  // the two loop RETURN_IFs of the ray-cast exit contract (kernel_record.h),
  // or if `leaf` holds anything but an epilogue.
  void ConfigRoboCore(std::shared_ptr<const MicroProgram> program,
                      std::shared_ptr<const MicroProgram> leaf = nullptr);
  // One layout per node kind the program may load; replaces earlier ones.
  void ConfigDecode(std::vector<NodeLayout> layouts);

  // Runs the batch on the host kernels, recording every node fetch. Without
  // ConfigRoboCore, the shipped program for the scene's method and the
  // beam-model leaf are used. Throws std::invalid_argument if ConfigDecode
  // was called and has no layout for the scene's node kind, or one whose
  // size disagrees with the structure in memory.
  void ExecuteRoboCore(const RayBatch& queries, const RayCastScene& scene,
                       std::vector<RayHit>& results, KernelRecord& record) const;

 private:
  std::shared_ptr<const MicroProgram> program_;
  std::shared_ptr<const MicroProgram> leaf_;
  bool leaf_configured_ = false;
  std::vector<NodeLayout> layouts_;
};

}  // namespace rc
