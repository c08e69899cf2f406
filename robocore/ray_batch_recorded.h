#pragma once
// CastRayBatch with a recording visitor: the same hits, plus the kernel
// record every backend prices (robocore/kernel_record.h).
//
// Two passes, parallel over queries with OpenMP and deterministic: the
// functional kernel for every query (its hit, its node count and which exit
// ended its last pass), a prefix sum of the counts into per-query slots
// (the CSR offsets), then the kernel again, for the queries whose addresses
// the sample keeps only, with a visitor that writes each fetch into the
// query's own slot. The record does not depend on the thread count. Cost:
// CastRayBatch, plus the kept fraction of it again, plus one 1-byte store
// per fetch and one 8-byte store per kept fetch; a record reused across
// batches keeps its capacity.
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
  // Whose addresses the record keeps (default: every query's).
  AddressSample sample;
};

void CastRayBatchRecorded(const RayCastScene& scene, const RayBatch& batch,
                          std::vector<RayHit>& hits, KernelRecord& record,
                          const RecordOptions& options = {});

// The regions a scene's kernel fetches from, placed by `layout`: the grid
// (1 byte per cell) for march and dda, the distance field (4 bytes per
// cell) for rm.
std::vector<MemoryRegion> RayCastRegions(const RayCastScene& scene, const DeviceLayout& layout);

}  // namespace rc
