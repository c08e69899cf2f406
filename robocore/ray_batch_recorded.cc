#include "robocore/ray_batch_recorded.h"

#include <omp.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "robocore/shipped_programs.h"

namespace rc {
namespace {

std::uint64_t AlignUp(std::uint64_t value, std::uint64_t alignment) {
  return (value + alignment - 1) / alignment * alignment;
}

// Appends the device address of every fetch and remembers the last index,
// so the caller can tell whether the last node stopped the ray.
struct RecordingVisitor {
  std::vector<std::uint64_t>* addresses;
  std::uint64_t base[2];
  std::uint32_t element_bytes[2];
  std::uint32_t last_index = 0;
  FetchKind last_kind = FetchKind::kGridCell;

  void Fetch(FetchKind kind, std::uint32_t index) {
    const int k = static_cast<int>(kind);
    addresses->push_back(base[k] + std::uint64_t{index} * element_bytes[k]);
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
  const long n = static_cast<long>(batch.queries.size());
  hits.resize(batch.queries.size());
  record = KernelRecord{};
  record.step_kind = StepProgramFor(scene.method());
  record.program = options.program ? options.program : ShippedStepProgram(record.step_kind);
  if (record.program->ReturnIfCount(ProgramSection::kLoop) <= kRayEndReturn)
    throw std::invalid_argument("ray-cast program '" + record.program->name() +
                                "' needs RETURN_IF #0 (hit) and #1 (end) in its loop");
  record.leaf_kind = options.leaf;
  record.leaf = ShippedLeafProgram(options.leaf);
  record.regions = RayCastRegions(scene, options.layout);
  record.node_bytes = record.regions.front().element_bytes;

  RecordingVisitor prototype{};
  for (const MemoryRegion& r : record.regions) {
    prototype.base[static_cast<int>(r.kind)] = r.base;
    prototype.element_bytes[static_cast<int>(r.kind)] = r.element_bytes;
  }

  // One contiguous chunk of queries per thread, each thread appending its
  // queries' fetches in query order; per-query counts are the slots.
  const int max_threads = std::max(1, omp_get_max_threads());
  std::vector<std::vector<std::uint64_t>> addresses(max_threads);
  std::vector<std::vector<std::uint8_t>> exits(max_threads);
  std::vector<long> chunk_begin(max_threads + 1, n);
  std::vector<std::uint64_t> counts(batch.queries.size());
#pragma omp parallel num_threads(max_threads)
  {
    const int t = omp_get_thread_num();
    const int threads = omp_get_num_threads();
    const long lo = n * t / threads, hi = n * (t + 1) / threads;
    chunk_begin[t] = lo;
    RecordingVisitor visitor = prototype;
    visitor.addresses = &addresses[t];
    for (long i = lo; i < hi; ++i) {
      const RayQuery& q = batch.queries[i];
      const std::size_t before = addresses[t].size();
      hits[i] = CastRay(scene, q.origin_x_m, q.origin_y_m, q.angle_rad, batch.max_range_m, visitor);
      counts[i] = addresses[t].size() - before;
      if (counts[i] > 0) {
        exits[t].insert(exits[t].end(), counts[i] - 1, kNoExit);
        exits[t].push_back(LastPassExit(scene, visitor));
      }
    }
  }

  record.fetch_offsets.assign(batch.queries.size() + 1, 0);
  for (long i = 0; i < n; ++i) record.fetch_offsets[i + 1] = record.fetch_offsets[i] + counts[i];
  record.fetch_addresses.resize(record.fetch_offsets.back());
  record.node_exits.resize(record.fetch_offsets.back());
#pragma omp parallel for schedule(static, 1) num_threads(max_threads)
  for (int t = 0; t < max_threads; ++t) {
    if (addresses[t].empty()) continue;
    const std::uint64_t at = record.fetch_offsets[chunk_begin[t]];
    std::memcpy(record.fetch_addresses.data() + at, addresses[t].data(),
                addresses[t].size() * sizeof(std::uint64_t));
    std::memcpy(record.node_exits.data() + at, exits[t].data(), exits[t].size());
  }
}

}  // namespace rc
