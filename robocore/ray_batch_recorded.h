#pragma once
// CastRayBatch with a recording visitor: the same hits, plus the kernel
// record every backend prices (robocore/kernel_record.h).
//
// Parallel over queries with OpenMP and deterministic: every query writes
// its fetches into its own slot, the slots' sizes are prefix-summed into
// the CSR offsets, and the slots are copied into place, so the record does
// not depend on the thread count. The cost over CastRayBatch is one 9-byte
// store per node fetch.
#include <vector>

#include "robocore/kernel_record.h"
#include "robocore/ray_batch.h"

namespace rc {

struct RecordOptions {
  DeviceLayout layout;
  // The artifact's DeliBot kernel evaluates the beam model in the leaf of
  // each ray (REFERENCE.md section 2); the host-side sensor model computes
  // the same quantity. kNone prices the traversal alone.
  LeafProgramKind leaf = LeafProgramKind::kBeamModel;
  // Null: the shipped program for the scene's method. A custom program
  // (ConfigRoboCore) must keep the exit contract of kRayHitReturn and
  // kRayEndReturn.
  std::shared_ptr<const MicroProgram> program;
};

void CastRayBatchRecorded(const RayCastScene& scene, const RayBatch& batch,
                          std::vector<RayHit>& hits, KernelRecord& record,
                          const RecordOptions& options = {});

// The regions a scene's kernel fetches from, placed by `layout`: the grid
// (1 byte per cell) for march and dda, the distance field (4 bytes per
// cell) for rm.
std::vector<MemoryRegion> RayCastRegions(const RayCastScene& scene, const DeviceLayout& layout);

}  // namespace rc
