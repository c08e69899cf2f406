#include "robocore/ray_batch_recorded.h"

#include <algorithm>
#include <stdexcept>

#include "robocore/ray_batch_lanes.h"
#include "robocore/shipped_programs.h"

namespace rc {
namespace {

bool ValidCellBytes(std::uint32_t bytes) { return bytes == 1 || bytes == 2 || bytes == 4 || bytes == 8; }

std::uint64_t AlignUp(std::uint64_t value, std::uint64_t alignment) {
  return (value + alignment - 1) / alignment * alignment;
}

// Remembers the last fetch, so the caller can tell whether the last node
// stopped the ray.
struct LastFetchVisitor {
  std::uint32_t last_index = 0;
  FetchKind last_kind = FetchKind::kGridCell;
  void Fetch(FetchKind kind, std::uint32_t index) {
    last_index = index;
    last_kind = kind;
  }
};

// Also marks, in a byte per sector of the footprint (LaneRecording::touched),
// the sector of every fetch (a sampled record counts the sectors the whole
// batch touched).
struct MarkingVisitor : LastFetchVisitor {
  std::uint8_t* touched = nullptr;
  std::uint64_t offset[2];  // region base - footprint begin
  std::uint32_t element_bytes[2];
  int sector_shift = 5;

  void Fetch(FetchKind kind, std::uint32_t index) {
    const int k = static_cast<int>(kind);
    touched[(offset[k] + std::uint64_t{index} * element_bytes[k]) >> sector_shift] = 1;
    LastFetchVisitor::Fetch(kind, index);
  }
};

// Also appends the index of every fetched node to a block's buffer (and
// marks its sector when `touched` is set). A ray kernel fetches one
// structure, so an index names its node (KeptBlockNodes).
struct RecordingVisitor : LastFetchVisitor {
  std::vector<std::uint32_t>* out = nullptr;
  std::uint8_t* touched = nullptr;
  FetchKind kept_kind = FetchKind::kGridCell;  // the structure whose nodes `out` indexes
  std::uint64_t offset[2];
  std::uint32_t element_bytes[2];
  int sector_shift = 5;

  void Fetch(FetchKind kind, std::uint32_t index) {
    const int k = static_cast<int>(kind);
    if (kind != kept_kind) throw std::logic_error("CastRayBatchRecorded: a ray kernel fetched a second structure");
    out->push_back(index);
    if (touched) touched[(offset[k] + std::uint64_t{index} * element_bytes[k]) >> sector_shift] = 1;
    LastFetchVisitor::Fetch(kind, index);
  }
};

// The RETURN_IF that ended the query's last loop pass (exit contract in
// kernel_record.h): the fetched cell stopped the ray, or the next one is out
// of range or off the map.
std::uint8_t LastPassExit(const RayCastScene& scene, const LastFetchVisitor& v) {
  const bool stops = v.last_kind == FetchKind::kDistanceCell ? scene.distance_field()->values()[v.last_index] == 0.0f
                                                             : scene.grid().cells()[v.last_index] != CellState::kFree;
  return stops ? kRayHitReturn : kRayEndReturn;
}

// The queries of one launch, in launch order: `count` of them, from
// `queries`, or written on demand by `fill` when `queries` is null.
struct LaunchQueries {
  const RayQuery* queries;
  std::size_t count;
  double max_range_m;
  const QueryFiller* fill = nullptr;

  // Queries [lo, hi): in place, or filled into `buffer`.
  const RayQuery* Range(long lo, long hi, std::vector<RayQuery>& buffer) const {
    if (queries) return queries + lo;
    buffer.resize(static_cast<std::size_t>(hi - lo));
    (*fill)(static_cast<std::size_t>(lo), static_cast<std::size_t>(hi), buffer.data());
    return buffer.data();
  }
  // Appends queries [lo, hi) to `out`.
  void Append(long lo, long hi, std::vector<RayQuery>& out) const {
    const std::size_t at = out.size();
    if (queries) {
      out.insert(out.end(), queries + lo, queries + hi);
      return;
    }
    out.resize(at + static_cast<std::size_t>(hi - lo));
    (*fill)(static_cast<std::size_t>(lo), static_cast<std::size_t>(hi), out.data() + at);
  }
};

// A thread's buffers, reused segment after segment: the lanes' node log,
// and the queries (gathered, or filled), hits and exits of a segment.
struct LaneBatchWork {
  LaneNodeLog log;
  std::vector<RayQuery> queries;
  std::vector<RayHit> hits;
  std::vector<std::uint8_t> exits;
};

// Per block of a launch, the node indices of its queries in launch order,
// for the blocks whose addresses the sample keeps (empty for the others).
// Indices, at 4 bytes a node, rather than addresses at 8: the record's
// addresses are written once, from them, straight into its array.
using KeptBlockNodes = std::vector<std::vector<std::uint32_t>>;

// Casts blocks (of `block` queries; ascending, not necessarily adjacent)
// in the lanes as one contiguous batch, then puts each query's hit and last
// exit in place and, for kept blocks (`kept_nodes` set), appends its
// node indices to its block's buffer. One batch rather than one per run
// of adjacent blocks: the lanes drain at a batch's end, idling while its
// last rays finish. Adjacent unkept blocks are cast in place, without the
// copies. `lane` says where to mark touched sectors.
void CastBlocksInLanes(const RayCastScene& scene, const LaunchQueries& launch, const std::vector<long>& blocks,
                       long block, LaneRecording lane, LaneBatchWork& work, RayHit* hits, std::uint8_t* last_exit,
                       KeptBlockNodes* kept_nodes) {
  const long n = static_cast<long>(launch.count);
  auto end_of = [&](long b) { return std::min(n, (b + 1) * block); };
  if (!kept_nodes && blocks.back() - blocks.front() + 1 == static_cast<long>(blocks.size())) {
    const long lo = blocks.front() * block, hi = end_of(blocks.back());
    lane.last_exits = last_exit + lo;
    lane.nodes = nullptr;
    CastRayLanes(scene, launch.Range(lo, hi, work.queries), static_cast<std::size_t>(hi - lo), launch.max_range_m,
                 hits + lo, &lane);
    return;
  }
  work.queries.clear();
  for (long b : blocks) launch.Append(b * block, end_of(b), work.queries);
  work.hits.resize(work.queries.size());
  work.exits.assign(work.queries.size(), kNoExit);
  lane.last_exits = work.exits.data();
  lane.nodes = kept_nodes ? &work.log : nullptr;
  CastRayLanes(scene, work.queries.data(), work.queries.size(), launch.max_range_m, work.hits.data(), &lane);
  std::size_t g = 0;  // position in the gathered batch
  for (long b : blocks) {
    const long lo = b * block, hi = end_of(b);
    std::copy(work.hits.begin() + static_cast<long>(g), work.hits.begin() + static_cast<long>(g) + (hi - lo),
              hits + lo);
    std::copy(work.exits.begin() + static_cast<long>(g), work.exits.begin() + static_cast<long>(g) + (hi - lo),
              last_exit + lo);
    if (!kept_nodes) {
      g += static_cast<std::size_t>(hi - lo);
      continue;
    }
    std::vector<std::uint32_t>& out = (*kept_nodes)[static_cast<std::size_t>(b)];
    std::size_t fetches = 0;
    for (std::size_t i = g; i < g + static_cast<std::size_t>(hi - lo); ++i) fetches += work.hits[i].nodes;
    out.resize(fetches);
    std::uint32_t* at = out.data();
    for (long i = lo; i < hi; ++i, ++g) {
      const std::uint32_t* index = work.log.NodesOf(g);
      at = std::copy(index, index + work.hits[g].nodes, at);
    }
  }
}

}  // namespace

const char* ToString(MarchProgramChoice choice) {
  return choice == MarchProgramChoice::kArtifact ? "artifact" : "shipped";
}

bool ParseMarchProgramChoice(const std::string& text, MarchProgramChoice* out) {
  for (MarchProgramChoice c : {MarchProgramChoice::kShipped, MarchProgramChoice::kArtifact})
    if (text == ToString(c)) return *out = c, true;
  return false;
}

bool RayKernelChoices::IsValid(std::string* error) const {
  if (ValidCellBytes(grid_cell_bytes)) return true;
  if (error) *error = "grid_cell_bytes must be 1, 2, 4 or 8, got " + std::to_string(grid_cell_bytes);
  return false;
}

RecordOptions RecordOptionsFor(RayCastMethod method, const RayKernelChoices& choices, RecordOptions base) {
  std::string error;
  if (!choices.IsValid(&error)) throw std::invalid_argument("ray kernel choices: " + error);
  base.layout.grid_cell_bytes = choices.grid_cell_bytes;
  if (method == RayCastMethod::kMarch && choices.march_program == MarchProgramChoice::kArtifact)
    base.program = ShippedProgram("grid_march_artifact.asm");
  return base;
}

std::vector<MemoryRegion> RayCastRegions(const RayCastScene& scene, const DeviceLayout& layout) {
  if (!ValidCellBytes(layout.grid_cell_bytes))
    throw std::invalid_argument("device layout: grid_cell_bytes must be 1, 2, 4 or 8, got " +
                                std::to_string(layout.grid_cell_bytes));
  const OccupancyGrid& g = scene.grid();
  MemoryRegion grid{"occupancy grid", FetchKind::kGridCell, AlignUp(layout.first_base, layout.alignment),
                    layout.grid_cell_bytes, g.cell_count()};
  if (scene.method() != RayCastMethod::kRayMarching) return {grid};
  // The distance field lives after the grid, at its own base, even though
  // rm never reads the grid: the two are distinct device allocations.
  MemoryRegion field{"distance field", FetchKind::kDistanceCell, AlignUp(grid.base + grid.bytes(), layout.alignment),
                     sizeof(float), scene.distance_field()->values().size()};
  return {field};
}

namespace {

// CastRayBatchRecorded's launch: its queries' hits go to hits[0, count).
void RecordLaunch(const RayCastScene& scene, const LaunchQueries& launch, RayHit* hits, KernelRecord& record,
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

  // One pass of the functional kernel, parallel over segments of queries:
  // each query's hit, node count and last pass's exit, and for the blocks
  // whose addresses the sample keeps, the node indices in a buffer per
  // block. A block is the GPU's (warps_per_block warps), so a block is kept
  // or not as a whole; the buffers are turned into the record's addresses
  // in launch order afterwards, so the record does not depend on the thread
  // count or the schedule.
  const AddressSample& sample = options.sample;
  const long n = static_cast<long>(launch.count);
  const long block = static_cast<long>(sample.BlockQueries());  // KeptAddressOffsets' blocks
  const long blocks = (n + block - 1) / block;
  std::vector<std::uint8_t>& last_exit = record.last_exits;
  last_exit.assign(launch.count, kNoExit);
  record.node_exits.clear();
  KeptBlockNodes kept_nodes(static_cast<std::size_t>(blocks));
  // A sample also counts the sectors the whole batch touches: a byte per
  // sector of the footprint per thread, ORed together afterwards.
  const bool mark = !sample.KeepsAll();
  int sector_shift = 0;
  while ((1 << sector_shift) < sample.sector_bytes) ++sector_shift;
  const std::uint64_t footprint_begin = record.footprint_begin();
  const std::uint64_t sectors = mark ? ((record.footprint_end() - footprint_begin) >> sector_shift) + 1 : 0;
  std::vector<std::vector<std::uint8_t>> touched;
  RecordingVisitor prototype{};
  for (const MemoryRegion& r : record.regions) {
    const int k = static_cast<int>(r.kind);
    prototype.offset[k] = r.base - footprint_begin;
    prototype.element_bytes[k] = r.element_bytes;
  }
  prototype.sector_shift = sector_shift;
  // Segments of the batch, each cast as a unit. With the SIMD lanes
  // (ray_batch_lanes.h, which also give the exits, touched sectors and node
  // indices), at most kLaneSegmentQueries queries each: kept blocks, or
  // unkept ones, gathered into one contiguous batch (a sample's kept blocks
  // lie apart and may cut the unkept ones into short runs, and the lanes
  // idle while a batch's last rays finish), except that a run of adjacent
  // unkept blocks of at least kInPlaceQueries queries is cast in place,
  // with no copies: its drain then costs less than copying its queries,
  // hits and exits would (docs/pricing.md, "The beam model's remaining
  // extra"). Several segments, so that two threads even out. Without the lanes: a run of at most
  // kSegmentQueries queries of unkept blocks (scalar, with the marking
  // visitor) or one kept block (scalar, with the recording visitor).
  constexpr long kSegmentQueries = 2048;
  constexpr long kLaneSegmentQueries = 8192;
  constexpr long kInPlaceQueries = 2048;
  struct Segment {
    std::vector<long> blocks;  // ascending; adjacent without the lanes
    long queries = 0;
    bool keep = false;
  };
  const bool lanes = RayLanesApply(scene);
  std::vector<Segment> segments;
  long open[2] = {-1, -1};  // the segment still taking blocks: unkept, kept
  for (long b = 0; b < blocks; ++b) {
    const long size = std::min(n, (b + 1) * block) - b * block;
    const bool keep = sample.KeepsQuery(static_cast<std::size_t>(b * block));
    long& last = open[keep];
    const bool adjacent = last >= 0 && segments[last].blocks.back() + 1 == b;
    const bool joins = last >= 0 && (lanes ? segments[last].queries + size <= kLaneSegmentQueries &&
                                                 (keep || adjacent || segments[last].queries < kInPlaceQueries)
                                           : !keep && segments[last].queries + size <= kSegmentQueries && adjacent);
    if (!joins) {
      last = static_cast<long>(segments.size());
      segments.push_back({{}, 0, keep});
    }
    segments[last].blocks.push_back(b);
    segments[last].queries += size;
  }
  const MemoryRegion& fetched = record.regions.front();  // a ray kernel fetches one structure
  // Where each block's fetches begin (entry b; the last entry is the total):
  // each block's node sum is written at b + 1 by the task that cast it,
  // while its hits are in that thread's caches, and summed up after the
  // cast, so that the fetch offsets can be written block by block in
  // parallel (docs/pricing.md, "A launch's record finished in parallel").
  std::vector<std::uint64_t> block_base(static_cast<std::size_t>(blocks) + 1, 0);
  auto sum_blocks = [&](const std::vector<long>& cast) {
    for (long b : cast) {
      std::uint64_t sum = 0;
      for (long i = b * block; i < std::min(n, (b + 1) * block); ++i) sum += hits[i].nodes;
      block_base[static_cast<std::size_t>(b) + 1] = sum;
    }
  };
#pragma omp parallel
  {
    std::vector<std::uint8_t> mine(mark ? sectors : 0, 0);
    LaneBatchWork lane_work;
#pragma omp for schedule(dynamic, 1)
    for (long j = 0; j < static_cast<long>(segments.size()); ++j) {
      const Segment& seg = segments[static_cast<std::size_t>(j)];
      const long lo = seg.blocks.front() * block;
      LaneRecording lane;
      lane.touched = mark ? mine.data() : nullptr;
      lane.offset = fetched.base - footprint_begin;
      lane.element_bytes = fetched.element_bytes;
      lane.sector_shift = sector_shift;
      if (lanes) {
        CastBlocksInLanes(scene, launch, seg.blocks, block, lane, lane_work, hits, last_exit.data(),
                          seg.keep ? &kept_nodes : nullptr);
      } else if (seg.keep) {
        RecordingVisitor recording = prototype;
        recording.out = &kept_nodes[static_cast<std::size_t>(seg.blocks.front())];
        recording.kept_kind = fetched.kind;
        recording.touched = mark ? mine.data() : nullptr;
        recording.out->reserve(static_cast<std::size_t>(seg.queries) * 32);
        const RayQuery* queries = launch.Range(lo, lo + seg.queries, lane_work.queries);
        for (long i = lo; i < lo + seg.queries; ++i) {
          const RayQuery& q = queries[i - lo];
          hits[i] = CastRay(scene, q.origin_x_m, q.origin_y_m, q.angle_rad, launch.max_range_m, recording);
          if (hits[i].nodes > 0) last_exit[i] = LastPassExit(scene, recording);
        }
      } else {
        MarkingVisitor marking;
        marking.touched = mine.data();
        for (int k = 0; k < 2; ++k) {
          marking.offset[k] = prototype.offset[k];
          marking.element_bytes[k] = prototype.element_bytes[k];
        }
        marking.sector_shift = sector_shift;
        const RayQuery* queries = launch.Range(lo, lo + seg.queries, lane_work.queries);
        for (long i = lo; i < lo + seg.queries; ++i) {
          const RayQuery& q = queries[i - lo];
          hits[i] = CastRay(scene, q.origin_x_m, q.origin_y_m, q.angle_rad, launch.max_range_m, marking);
          if (hits[i].nodes > 0) last_exit[i] = LastPassExit(scene, marking);
        }
      }
      sum_blocks(seg.blocks);
    }
#pragma omp critical(rc_touched_sectors)
    touched.push_back(std::move(mine));
  }
  // The threads' touched sectors ORed and counted, a range of sectors each.
  std::uint64_t touched_count = 0;
  if (mark) {
    constexpr long kSectorChunk = 1 << 14;
    const long chunks = static_cast<long>((sectors + kSectorChunk - 1) / kSectorChunk);
#pragma omp parallel for schedule(static) reduction(+ : touched_count)
    for (long c = 0; c < chunks; ++c) {
      const long lo = c * kSectorChunk, hi = std::min(static_cast<long>(sectors), lo + kSectorChunk);
      std::uint8_t* all = touched.front().data();
      for (std::size_t t = 1; t < touched.size(); ++t)
        for (long w = lo; w < hi; ++w) all[w] |= touched[t][w];
      for (long w = lo; w < hi; ++w) touched_count += all[w] != 0;
    }
  }
  record.touched_sectors = touched_count;

  // Prefix sums, every entry written: resize, not assign, so that a reused
  // record's vectors are not first filled with zeros. Each block's from its
  // base, in parallel; within a block the running sum stays in a register:
  // reading each entry back would wait on its store.
  for (long b = 0; b < blocks; ++b) block_base[b + 1] += block_base[b];
  record.fetch_offsets.resize(launch.count + 1);
  std::uint64_t* offsets = record.fetch_offsets.data();
  offsets[0] = 0;
#pragma omp parallel for schedule(static)
  for (long b = 0; b < blocks; ++b) {
    std::uint64_t sum = block_base[b];
    for (long i = b * block; i < std::min(n, (b + 1) * block); ++i) offsets[i + 1] = sum += hits[i].nodes;
  }
  record.address_sample = sample;
  if (sample.KeepsAll())
    record.address_offsets.clear();
  else
    record.address_offsets = KeptAddressOffsets(record.fetch_offsets, sample);
  std::vector<std::uint64_t> block_start(static_cast<std::size_t>(blocks) + 1, 0);
  for (long b = 0; b < blocks; ++b) block_start[b + 1] = block_start[b] + kept_nodes[b].size();
  const std::uint64_t kept = sample.KeepsAll() ? record.fetch_offsets.back() : record.address_offsets.back();
  if (block_start.back() != kept) throw std::logic_error("CastRayBatchRecorded: a kept block lost fetches");
  record.fetch_addresses.resize(kept);
  std::uint64_t* const addresses = record.fetch_addresses.data();
  // A 32-bit index times a 32-bit size: one 32x32->64 multiply per address
  // (a 64-bit element size made it a 64x64 one, three in SSE2).
  const std::uint64_t base = fetched.base;
  const std::uint32_t element_bytes = fetched.element_bytes;
#pragma omp parallel for schedule(static)
  for (long b = 0; b < blocks; ++b) {
    const std::uint32_t* index = kept_nodes[b].data();
    std::uint64_t* out = addresses + block_start[b];
    for (std::size_t k = 0; k < kept_nodes[b].size(); ++k) out[k] = base + std::uint64_t{index[k]} * element_bytes;
  }
}

}  // namespace

void CastRayBatchRecorded(const RayCastScene& scene, const RayBatch& batch, std::vector<RayHit>& hits,
                          KernelRecord& record, const RecordOptions& options) {
  hits.resize(batch.queries.size());
  RecordLaunch(scene, {batch.queries.data(), batch.queries.size(), batch.max_range_m}, hits.data(), record, options);
}

void CastRayBatchRecordedFilled(const RayCastScene& scene, std::size_t count, double max_range_m,
                                const QueryFiller& fill, std::vector<RayHit>& hits, KernelRecord& record,
                                const RecordOptions& options) {
  if (hits.size() != count) throw std::invalid_argument("CastRayBatchRecordedFilled: hits must hold count entries");
  RecordLaunch(scene, {nullptr, count, max_range_m, &fill}, hits.data(), record, options);
}

}  // namespace rc
