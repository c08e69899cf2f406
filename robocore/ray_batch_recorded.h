#pragma once
// CastRayBatch with a recording visitor: the same hits, plus the kernel
// record every backend prices (robocore/kernel_record.h).
//
// One pass of the kernel, parallel over segments of queries with OpenMP and
// deterministic: every query's hit, node count and last pass's exit; the
// node indices of the blocks the sample keeps, in a buffer per block, turned
// into the record's addresses in launch order; and, with a sample, the
// sectors the whole batch touched.
// Where CastRayBatch's SIMD lanes apply (ray_batch_lanes.h), every query
// is cast in them, the kept ones with each lane's node indices logged;
// elsewhere one query at a time, the kept ones with a recording visitor.
// The record does not depend on the thread count or the path.
// Cost: about CastRayBatch, plus a 4-byte and an 8-byte store per kept
// fetch; a record reused across batches keeps its capacity.
#include <functional>
#include <string>
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

// The kernel-side choices a backend preset makes for the ray casts
// (backends/presets/*.json, its "kernel" object): how the device stores the
// occupancy grid, and which cost description the RT units run for march.
// Neither changes a functional answer.
enum class MarchProgramChoice : std::uint8_t {
  kShipped,   // programs/grid_march.asm: the micro-ops CastMarch performs, 1-byte cells
  kArtifact,  // programs/grid_march_artifact.asm: the artifact's 7-op cell transaction
};
const char* ToString(MarchProgramChoice choice);  // "shipped" | "artifact"
bool ParseMarchProgramChoice(const std::string& text, MarchProgramChoice* out);

struct RayKernelChoices {
  std::uint32_t grid_cell_bytes = 1;  // bytes per occupancy cell on the device: 1, 2, 4 or 8
  MarchProgramChoice march_program = MarchProgramChoice::kShipped;
  bool IsValid(std::string* error) const;
};

// `base` with the choices applied for a scene of `method`: the layout's
// cell size, and for march the chosen program (other methods keep theirs).
// Throws std::invalid_argument for invalid choices.
RecordOptions RecordOptionsFor(RayCastMethod method, const RayKernelChoices& choices, RecordOptions base = {});

void CastRayBatchRecorded(const RayCastScene& scene, const RayBatch& batch, std::vector<RayHit>& hits,
                          KernelRecord& record, const RecordOptions& options = {});

// Writes queries [begin, end) of a launch to out[0, end - begin). Called
// from several threads at once, each time for a different range; the same
// range must always give the same queries.
using QueryFiller = std::function<void(std::size_t begin, std::size_t end, RayQuery* out)>;

// The same for a launch of `count` queries that `fill` writes segment by
// segment as they are cast, so that they never exist all at once (a
// beam-model launch of 2^20 rays would hold 24 MB of them); the record is
// the one CastRayBatchRecorded gives for the batch of those queries, and
// the hits go to hits [0, count) (hits must hold count entries). Throws
// std::invalid_argument for hits of another size.
void CastRayBatchRecordedFilled(const RayCastScene& scene, std::size_t count, double max_range_m,
                                const QueryFiller& fill, std::vector<RayHit>& hits, KernelRecord& record,
                                const RecordOptions& options = {});

// The regions a scene's kernel fetches from, placed by `layout`: the grid
// (layout.grid_cell_bytes per cell) for march and dda, the distance field
// (4 bytes per cell) for rm. Throws std::invalid_argument for a cell size
// other than 1, 2, 4 or 8 bytes.
std::vector<MemoryRegion> RayCastRegions(const RayCastScene& scene, const DeviceLayout& layout);

}  // namespace rc
