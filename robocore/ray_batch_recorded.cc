#include "robocore/ray_batch_recorded.h"

#include <algorithm>
#include <stdexcept>

#include "robocore/shipped_programs.h"

namespace rc {
namespace {

std::uint64_t AlignUp(std::uint64_t value, std::uint64_t alignment) {
  return (value + alignment - 1) / alignment * alignment;
}

// Writes the device address of every fetch into the query's slot and
// remembers the last index, so the caller can tell whether the last node
// stopped the ray.
struct RecordingVisitor {
  std::uint64_t* next = nullptr;
  std::uint64_t base[2];
  std::uint32_t element_bytes[2];
  std::uint32_t last_index = 0;
  FetchKind last_kind = FetchKind::kGridCell;

  void Fetch(FetchKind kind, std::uint32_t index) {
    const int k = static_cast<int>(kind);
    *next++ = base[k] + std::uint64_t{index} * element_bytes[k];
    last_index = index;
    last_kind = kind;
  }
};

// The RETURN_IF that ended the query's last loop pass (exit contract in
// kernel_record.h): the fetched cell stopped the ray, or the next one is out
// of range or off the map.
std::uint8_t LastPassExit(const RayCastScene& scene, const RecordingVisitor& v) {
  const bool stops = v.last_kind == FetchKind::kDistanceCell
                         ? scene.distance_field()->values()[v.last_index] == 0.0f
                         : scene.grid().cells()[v.last_index] != CellState::kFree;
  return stops ? kRayHitReturn : kRayEndReturn;
}

}  // namespace

std::vector<MemoryRegion> RayCastRegions(const RayCastScene& scene, const DeviceLayout& layout) {
  const OccupancyGrid& g = scene.grid();
  MemoryRegion grid{"occupancy grid", FetchKind::kGridCell, AlignUp(layout.first_base, layout.alignment),
                    sizeof(CellState), g.cell_count()};
  if (scene.method() != RayCastMethod::kRayMarching) return {grid};
  // The distance field lives after the grid, at its own base, even though
  // rm never reads the grid: the two are distinct device allocations.
  MemoryRegion field{"distance field", FetchKind::kDistanceCell,
                     AlignUp(grid.base + grid.bytes(), layout.alignment), sizeof(float),
                     scene.distance_field()->values().size()};
  return {field};
}

void CastRayBatchRecorded(const RayCastScene& scene, const RayBatch& batch,
                          std::vector<RayHit>& hits, KernelRecord& record,
                          const RecordOptions& options) {
  record.step_kind = StepProgramFor(scene.method());
  record.program = options.program ? options.program : ShippedStepProgram(record.step_kind);
  if (record.program->ReturnIfCount(ProgramSection::kLoop) <= kRayEndReturn)
    throw std::invalid_argument("ray-cast program '" + record.program->name() +
                                "' needs RETURN_IF #0 (hit) and #1 (end) in its loop");
  record.leaf_kind = options.leaf;
  record.leaf = ShippedLeafProgram(options.leaf);
  record.regions = RayCastRegions(scene, options.layout);
  record.node_bytes = record.regions.front().element_bytes;

  // Pass 1, the functional kernel itself: the hits, and each query's node
  // count, which sizes its slot. A prefix sum places the slots.
  CastRayBatch(scene, batch, hits);
  const long n = static_cast<long>(batch.queries.size());
  record.fetch_offsets.assign(batch.queries.size() + 1, 0);
  for (long i = 0; i < n; ++i) record.fetch_offsets[i + 1] = record.fetch_offsets[i] + hits[i].nodes;
  // resize keeps the capacity of a record reused across batches.
  record.fetch_addresses.resize(record.fetch_offsets.back());
  record.node_exits.resize(record.fetch_offsets.back());

  // Pass 2: every query writes its fetches into its own slot, so the record
  // does not depend on the thread count or the schedule.
  RecordingVisitor prototype{};
  for (const MemoryRegion& r : record.regions) {
    prototype.base[static_cast<int>(r.kind)] = r.base;
    prototype.element_bytes[static_cast<int>(r.kind)] = r.element_bytes;
  }
  bool mismatch = false;
#pragma omp parallel for schedule(dynamic, 256) reduction(|| : mismatch)
  for (long i = 0; i < n; ++i) {
    const RayQuery& q = batch.queries[i];
    RecordingVisitor visitor = prototype;
    visitor.next = record.fetch_addresses.data() + record.fetch_offsets[i];
    CastRay(scene, q.origin_x_m, q.origin_y_m, q.angle_rad, batch.max_range_m, visitor);
    const std::uint64_t begin = record.fetch_offsets[i], end = record.fetch_offsets[i + 1];
    mismatch = mismatch || visitor.next != record.fetch_addresses.data() + end;
    if (end == begin) continue;
    std::fill(record.node_exits.begin() + begin, record.node_exits.begin() + end - 1, kNoExit);
    record.node_exits[end - 1] = LastPassExit(scene, visitor);
  }
  if (mismatch) throw std::logic_error("CastRayBatchRecorded: the kernel fetched differently twice");
}

}  // namespace rc
