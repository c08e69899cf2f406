#pragma once
// What the lane kernels of every instruction set share (internal to
// robocore/ray_batch_lanes*.cc): the per-lane state kept in memory between
// rounds, a ray's set-up, the refill of lanes whose ray ended, and the
// recording's bookkeeping. Everything here is scalar code with no target
// attribute, so that each kernel file, compiled for its own instruction set,
// may inline it; the vector steps live in ray_lane_steps.inc, over each
// instruction set's operations (ray_lanes_avx512.cc, ray_lanes_avx2.cc),
// the loop that drives them in ray_lane_loop.inc.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "robocore/kernel_record.h"
#include "robocore/ray_batch_lanes.h"

namespace rc::ray_lanes {

inline constexpr int kLanes = kRaysInFlight;
using LaneMask = std::uint64_t;
static_assert(kLanes <= 64, "LaneMask holds one bit per lane");

inline constexpr double kInf = std::numeric_limits<double>::infinity();

// Per-lane state, in memory between rounds, in lane order: a group of W
// lanes is W consecutive entries of each array. The per-ray constants are
// ray_cast_detail::MakeAxis's values for each axis, plus the offsets that
// turn a cell into the boundary CastRay's Axis::BoundaryTime (exit) and
// EntryTime use, and limits that give a zero direction component CastRay's
// +inf exit and -inf entry: a zero inv_dir makes the formula's time +-0, and
// max(+-0, +inf) = +inf, min(+-0, -inf) = -inf, while for step != 0
// max(t, -inf) = min(t, +inf) = t.
struct alignas(64) LaneState {
  double origin_x[kLanes], origin_y[kLanes];
  double dir_x[kLanes], dir_y[kLanes];
  double inv_x[kLanes], inv_y[kLanes];
  double exit_limit_x[kLanes], exit_limit_y[kLanes];
  double entry_limit_x[kLanes], entry_limit_y[kLanes];
  double t_enter[kLanes];
  double exit_x[kLanes], exit_y[kLanes];  // dda: the current cell's exit times
  double range[kLanes];                   // the hit's range if the ray ended this round
  std::int32_t step_x[kLanes], step_y[kLanes];
  std::int32_t exit_offset_x[kLanes], exit_offset_y[kLanes];
  std::int32_t entry_offset_x[kLanes], entry_offset_y[kLanes];
  std::int32_t ix[kLanes], iy[kLanes];
  std::int32_t sample[kLanes];  // march: the index k of the next sample, at t = k r
  std::uint32_t nodes[kLanes];
  std::size_t query[kLanes];
  // A node log's write position in each lane's buffer, and the buffer's
  // end; there is always a slot at the position (LogNodes).
  std::uint32_t* log_at[kLanes];
  std::uint32_t* log_end[kLanes];
};

// The scene's scalars every step reads; each kernel broadcasts them once
// per call.
struct LaneScene {
  const void* cells = nullptr;   // dda, march: the grid's gather cells
  const float* field = nullptr;  // rm: the distance field
  double r = 0.0;                // cell size, m
  double max_range = 0.0;        // m
  double jump_margin = 0.0;      // rm: CastRayMarching's margin, computed as it computes it
  std::int32_t size_x = 0, size_y = 0;
  std::int32_t march_samples = 0;  // march: CastMarch's last sample index, floor(max_range / r)
  std::size_t cell_count = 0;      // one past the largest cell index a lane may fetch
};

// CastMarch's last sample index.
inline long MarchSamples(const OccupancyGrid& g, double max_range) {
  return static_cast<long>(std::floor(max_range / g.resolution_m()));
}

inline std::uint64_t DoubleBits(double x) {
  std::uint64_t u;
  std::memcpy(&u, &x, sizeof u);
  return u;
}
inline double BitsDouble(std::uint64_t u) {
  double x;
  std::memcpy(&x, &u, sizeof x);
  return x;
}
// c ? a : b on doubles without a branch (a mispredicted branch per ray on
// the sign of its direction is what this avoids).
inline double SelectDouble(bool c, double a, double b) {
  const std::uint64_t m = -static_cast<std::uint64_t>(c);
  return BitsDouble((DoubleBits(a) & m) | (DoubleBits(b) & ~m));
}
// static_cast<int>(std::floor(x)) for |x| < 2^31, without a branch.
inline int FloorToInt(double x) {
  const int i = static_cast<int>(x);
  return i - static_cast<int>(x < static_cast<double>(i));
}

// One axis of a lane's set-up: MakeAxis, the start cell and its exit time
// (Axis::BoundaryTime), the same operations without a branch. Scalar: rays
// end one lane at a time, and a vector set-up of one lane measured 2-6%
// slower (its vector loads wait on the scalar stores just made).
inline void SetUpAxisLane(int l, double o, double d, double r, double* origin, double* dir, double* inv_a,
                          std::int32_t* step_a, std::int32_t* exit_off_a, std::int32_t* entry_off_a, double* exit_lim_a,
                          double* entry_lim_a, std::int32_t* cell_a, double* exit_a) {
  const bool pos = d > 0.0, neg = d < 0.0, moves = pos | neg;
  const double inv = SelectDouble(moves, 1.0 / d, 0.0);
  const int exit_off = static_cast<int>(pos);
  const double exit_lim = SelectDouble(moves, -kInf, kInf);
  const int cell = FloorToInt(o / r);
  origin[l] = o;
  dir[l] = d;
  inv_a[l] = inv;
  step_a[l] = static_cast<int>(pos) - static_cast<int>(neg);
  exit_off_a[l] = exit_off;
  entry_off_a[l] = 1 - exit_off;
  exit_lim_a[l] = exit_lim;
  entry_lim_a[l] = SelectDouble(moves, kInf, -kInf);
  cell_a[l] = cell;
  const double t = (static_cast<double>(cell + exit_off) * r - o) * inv;
  exit_a[l] = t < exit_lim ? exit_lim : t;  // max_pd(limit, t)
}

// Starts query q in lane l (scalar: one ray).
inline void StartLane(LaneState& s, int l, const RayQuery& q, std::size_t index, double r) {
  const double dx = std::cos(q.angle_rad), dy = std::sin(q.angle_rad);
  SetUpAxisLane(l, q.origin_x_m, dx, r, s.origin_x, s.dir_x, s.inv_x, s.step_x, s.exit_offset_x, s.entry_offset_x,
                s.exit_limit_x, s.entry_limit_x, s.ix, s.exit_x);
  SetUpAxisLane(l, q.origin_y_m, dy, r, s.origin_y, s.dir_y, s.inv_y, s.step_y, s.exit_offset_y, s.entry_offset_y,
                s.exit_limit_y, s.entry_limit_y, s.iy, s.exit_y);
  s.t_enter[l] = 0.0;
  s.sample[l] = 0;
  s.nodes[l] = 0;
  s.query[l] = index;
}

// Notes where the query now in lane l begins in the lane's log.
inline void LogStart(const LaneState& s, int l, LaneNodeLog& log) {
  log.lane_of[s.query[l]] = static_cast<std::uint32_t>(l);
  log.start_of[s.query[l]] = static_cast<std::uint32_t>(s.log_at[l] - log.lane[l].data());
}

// What a recording notes as rays end and start (RunLaneLoop with a
// recording): each ended query's last loop pass's exit
// (LaneRecording::last_exits; `stopped`: the lanes whose fetched cell
// stopped them this round) and where each started query's nodes begin in
// its lane's log. Null: not wanted.
struct RefillNotes {
  std::uint8_t* last_exits = nullptr;
  LaneMask stopped = 0;
  LaneNodeLog* log = nullptr;
};

// Writes the hits of the lanes in `ended` and starts the batch's next
// queries in them; lanes left without one leave `live`. With kNotes, also
// notes what `notes` asks for, in the same pass over the ended lanes.
template <bool kNotes>
inline void Refill(LaneState& s, LaneMask ended, const RayQuery* queries, std::size_t count, std::size_t& next,
                   LaneMask& live, RayHit* hits, double r, const RefillNotes& notes) {
  while (ended != 0) {
    const int l = __builtin_ctzll(ended);
    ended &= ended - 1;
    RayHit& hit = hits[s.query[l]];
    hit.range_m = static_cast<float>(s.range[l]);
    hit.nodes = s.nodes[l];
    if constexpr (kNotes) {
      if (notes.last_exits)
        notes.last_exits[s.query[l]] = s.nodes[l] == 0            ? kNoExit
                                       : (notes.stopped >> l) & 1 ? kRayHitReturn
                                                                  : kRayEndReturn;
    }
    if (next == count) {
      live &= ~(LaneMask{1} << l);
      continue;
    }
    StartLane(s, l, queries[next], next, r);
    if constexpr (kNotes) {
      if (notes.log) LogStart(s, l, *notes.log);
    }
    ++next;
  }
}

// Starts every lane: the first kLanes queries, and lanes beyond the batch on
// a copy of its last query, not live. Returns the live mask.
inline LaneMask StartAll(LaneState& s, const RayQuery* queries, std::size_t count, std::size_t& next, double r) {
  LaneMask live = 0;
  for (int l = 0; l < kLanes; ++l) {
    const std::size_t q = next < count ? next : count - 1;
    if (next < count) {
      live |= LaneMask{1} << l;
      ++next;
    }
    StartLane(s, l, queries[q], q, r);
  }
  return live;
}

// Points each lane's write position at the start of its buffer in `log`
// (which keeps its size from call to call: entries past a lane's last
// query's nodes are scratch), with room for at least one node.
inline void StartNodeLog(LaneState& s, LaneNodeLog& log) {
  constexpr std::size_t kFirstSize = 256;
  for (int l = 0; l < kLanes; ++l) {
    std::vector<std::uint32_t>& lane = log.lane[l];
    if (lane.size() < kFirstSize) lane.resize(kFirstSize);
    s.log_at[l] = lane.data();
    s.log_end[l] = lane.data() + lane.size();
  }
}

// Notes where the queries now in `lanes` begin in their lanes' logs (the
// first ones; Refill notes those that follow).
inline void LogStarts(const LaneState& s, LaneMask lanes, LaneNodeLog& log) {
  for (; lanes != 0; lanes &= lanes - 1) LogStart(s, __builtin_ctzll(lanes), log);
}

// Doubles lane l's buffer, whose write position has reached its end, and
// returns the position in the new buffer. Rare: buffers keep their size.
[[gnu::noinline, gnu::cold]] inline std::uint32_t* GrowNodeLog(LaneState& s, int l, LaneNodeLog& log) {
  std::vector<std::uint32_t>& lane = log.lane[l];
  const std::size_t at = lane.size();
  lane.resize(2 * at);
  s.log_end[l] = lane.data() + lane.size();
  return lane.data() + at;
}

// Appends the fetched cells of a group of kWidth lanes (lanes first, first
// + 1, ...: bit i of `fetch` for lane first + i, index[i] its cell) to their
// lanes' logs. Without a branch per lane (which lanes fetched does not
// follow a pattern the predictor learns): every lane writes its cell at its
// position, and only a lane that fetched moves on, so a lane that did not
// leaves scratch that its next node overwrites.
template <int kWidth>
inline void LogNodes(LaneState& s, const std::int32_t* index, unsigned fetch, int first, LaneNodeLog& log) {
  for (int i = 0; i < kWidth; ++i) {
    const int l = first + i;
    std::uint32_t* at = s.log_at[l];
    *at = static_cast<std::uint32_t>(index[i]);
    at += (fetch >> i) & 1u;
    if (__builtin_expect(at == s.log_end[l], 0)) at = GrowNodeLog(s, l, log);
    s.log_at[l] = at;
  }
}

// How a recording finds a fetched cell's sector: the sector of byte
// offset + index * element_bytes. Where the fetched structure starts on a
// sector and its cells are a power of two no wider than one, that is
// first + (index >> index_shift), in 32 bits: a shift and an add, where the
// general form takes 64-bit multiplies (and in AVX-512 a scatter with 64-bit
// indices: several times the cost per step).
struct SectorOfCell {
  bool narrow = false;
  std::int32_t first = 0;
  int index_shift = 0;

  SectorOfCell() = default;
  // `cells`: one past the largest index fetched.
  SectorOfCell(const LaneRecording& rec, std::size_t cells) {
    const std::uint64_t sector_bytes = std::uint64_t{1} << rec.sector_shift;
    const std::uint32_t bytes = rec.element_bytes;
    if (rec.offset % sector_bytes != 0 || bytes == 0 || (bytes & (bytes - 1)) != 0 || bytes > sector_bytes) return;
    while ((std::uint64_t{bytes} << index_shift) < sector_bytes) ++index_shift;
    const std::uint64_t first_sector = rec.offset >> rec.sector_shift;
    if (first_sector + (cells >> index_shift) > static_cast<std::uint64_t>(std::numeric_limits<std::int32_t>::max()))
      return;
    narrow = true;
    first = static_cast<std::int32_t>(first_sector);
  }
};

// Sectors a lane kernel fetched from, queued as it steps and marked in a
// recording's touched bytes a few thousand at a time (Mark). A step appends
// its group's sectors with one vector store. Marking each step's sectors at
// once cost more, whether by an AVX-512 scatter or by a store per lane
// (docs/pricing.md, "Touched sectors in a queue").
class SectorQueue {
 public:
  static constexpr std::size_t kCapacity = 4096;  // entries queued before they are marked
  static constexpr std::size_t kMaxAppend = 16;   // entries one Append may write

  explicit SectorQueue(std::uint8_t* touched)
      : touched_(touched), entries_(touched ? kCapacity + kMaxAppend : 0), at_(entries_.data()) {}
  // Not copyable: the write position points into the queue's own entries.
  SectorQueue(const SectorQueue&) = delete;
  SectorQueue& operator=(const SectorQueue&) = delete;
  // Where the next entries go: room for kMaxAppend.
  std::uint32_t* end() { return at_; }
  // The `count` entries just written at end() join the queue.
  void Append(std::size_t count) {
    at_ += count;
    if (__builtin_expect(at_ >= entries_.data() + kCapacity, 0)) Mark();
  }
  // Marks every queued sector and empties the queue. A recording's marks are
  // complete only after its last Mark. Not inlined: in the lane loop it
  // would crowd the steps' registers.
  [[gnu::noinline]] void Mark() {
    std::uint8_t* const touched = touched_;
    const std::uint32_t* const end = at_;
#pragma GCC unroll 8
    for (const std::uint32_t* e = entries_.data(); e < end; ++e) touched[*e] = 1;
    at_ = entries_.data();
  }

 private:
  std::uint8_t* touched_;
  std::vector<std::uint32_t> entries_;
  std::uint32_t* at_;
};

// The instruction-set kernels (ray_lanes_avx512.cc, ray_lanes_avx2.cc):
// CastRayLanes for queries [0, count), count > 0, with `scene` as the lanes
// read it; the caller has checked that the CPU runs the instruction set.
void CastLanesAvx512(RayCastMethod method, const LaneScene& scene, const RayQuery* queries, std::size_t count,
                     RayHit* hits, const LaneRecording* recording);
void CastLanesAvx2(RayCastMethod method, const LaneScene& scene, const RayQuery* queries, std::size_t count,
                   RayHit* hits, const LaneRecording* recording);

}  // namespace rc::ray_lanes
