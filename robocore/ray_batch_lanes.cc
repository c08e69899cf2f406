#include "robocore/ray_batch_lanes.h"

#include "robocore/kernel_record.h"

#include <stdexcept>

#if defined(__x86_64__)
// GCC 12 warns of an uninitialized variable inside its own AVX-512 headers
// (the masked forms' _mm512_undefined_pd source); the warning is not ours.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"
#include <immintrin.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace rc {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

constexpr int kGroups = kRayLaneGroups;
constexpr int kLanes = kRaysInFlight;
using LaneMask = std::uint64_t;
static_assert(kLanes <= 64, "LaneMask holds one bit per lane");

// Per-lane state, in memory between rounds. The per-ray constants are
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
};

#define RC_LANES_TARGET __attribute__((target("avx512f,avx512vl,avx512dq")))

// The vector form of one axis's boundary time, (double(cell + offset) * r -
// origin) * inv, then the limit: max_pd(limit, t) is (t < limit) ? limit : t
// (exit), min_pd(limit, t) is (limit < t) ? limit : t (entry).
RC_LANES_TARGET inline __m512d BoundaryTime(__m256i cell, __m256i offset, __m512d r, __m512d origin, __m512d inv) {
  const __m512d b = _mm512_cvtepi32_pd(_mm256_add_epi32(cell, offset));
  return _mm512_mul_pd(_mm512_sub_pd(_mm512_mul_pd(b, r), origin), inv);
}

// The head of a loop pass of both kernels: a ray at or beyond max range
// ends at max range; one outside the map ends where it left; otherwise it
// fetches its cell. Returns the fetch mask; sets the cell indices and the
// range the ray has if it ends now, min_pd(max, t) = (max < t) ? max : t,
// which is CastRay's (t >= max) ? max : t.
struct Head {
  __mmask8 fetch;
  __m256i index;
  __m512d range;
};
RC_LANES_TARGET inline Head LoopHead(__m512d t, __m256i ix, __m256i iy, __m512d max_range, __m256i size_x,
                                     __m256i size_y) {
  Head h;
  const __mmask8 in_range = _mm512_cmp_pd_mask(t, max_range, _CMP_LT_OQ);
  const __mmask8 inside = _mm256_cmplt_epu32_mask(ix, size_x) & _mm256_cmplt_epu32_mask(iy, size_y);
  h.fetch = in_range & inside;
  h.index = _mm256_add_epi32(_mm256_mullo_epi32(ix, size_y), iy);
  h.range = _mm512_min_pd(max_range, t);
  return h;
}

// CastMarch's last sample index.
long MarchSamples(const OccupancyGrid& g, double max_range) {
  return static_cast<long>(std::floor(max_range / g.resolution_m()));
}

struct Constants {
  __m512d r, max_range, jump_margin;
  __m256i size_x, size_y, one, byte_mask;
  __m256i march_samples;  // CastMarch's last sample index, floor(max_range / r)
};

RC_LANES_TARGET Constants MakeConstants(const OccupancyGrid& g, double max_range) {
  Constants c;
  const double r = g.resolution_m();
  c.r = _mm512_set1_pd(r);
  c.max_range = _mm512_set1_pd(max_range);
  // CastRayMarching's margin, computed as it computes it.
  c.jump_margin = _mm512_set1_pd((std::sqrt(2.0) + 0.5) * r);
  c.size_x = _mm256_set1_epi32(g.size_x());
  c.size_y = _mm256_set1_epi32(g.size_y());
  c.one = _mm256_set1_epi32(1);
  c.byte_mask = _mm256_set1_epi32(0xFF);
  c.march_samples = _mm256_set1_epi32(static_cast<int>(MarchSamples(g, max_range)));
  return c;
}

#define RC_LOAD_I(field) _mm256_load_si256(reinterpret_cast<const __m256i*>(s.field + base))
#define RC_STORE_I(field, v) _mm256_store_si256(reinterpret_cast<__m256i*>(s.field + base), v)

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

// Writes the hits of the lanes in `ended` and starts the batch's next
// queries in them; lanes left without one leave `live`.
RC_LANES_TARGET void Refill(LaneState& s, LaneMask ended, const RayQuery* queries, std::size_t count, std::size_t& next,
                            LaneMask& live, RayHit* hits, double r) {
  while (ended != 0) {
    const int l = __builtin_ctzll(ended);
    ended &= ended - 1;
    RayHit& hit = hits[s.query[l]];
    hit.range_m = static_cast<float>(s.range[l]);
    hit.nodes = s.nodes[l];
    if (next == count) {
      live &= ~(LaneMask{1} << l);
      continue;
    }
    StartLane(s, l, queries[next], next, r);
    ++next;
  }
}

// Starts every lane: the first kLanes queries, and lanes beyond the batch on
// a copy of its last query, not live. Returns the live mask.
RC_LANES_TARGET LaneMask StartAll(LaneState& s, const RayQuery* queries, std::size_t count, std::size_t& next,
                                  double r) {
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

// What one pass of a group did: the lanes whose ray ended (hit range in
// s.range), those of them whose fetched cell stopped the ray, and the
// lanes that fetched, with their cell indices.
struct StepResult {
  __mmask8 ended, stopped, fetch;
  __m256i index;
};

// One pass of CastDda's loop for the lanes of group g.
RC_LANES_TARGET inline StepResult StepDdaGroup(LaneState& s, int g, const Constants& c, const void* cells) {
  const int base = g * kRayLanes;
  __m512d t = _mm512_load_pd(s.t_enter + base);
  __m512d tx = _mm512_load_pd(s.exit_x + base), ty = _mm512_load_pd(s.exit_y + base);
  __m256i ix = RC_LOAD_I(ix), iy = RC_LOAD_I(iy), nodes = RC_LOAD_I(nodes);
  const Head h = LoopHead(t, ix, iy, c.max_range, c.size_x, c.size_y);
  const __m256i cell =
      _mm256_and_si256(_mm256_mmask_i32gather_epi32(_mm256_setzero_si256(), h.fetch, h.index, cells, 1), c.byte_mask);
  const __mmask8 open = _mm256_cmpeq_epi32_mask(cell, _mm256_setzero_si256());  // CellState::kFree
  nodes = _mm256_mask_add_epi32(nodes, h.fetch, nodes, c.one);
  // CastDda's step: x first on a tie (tx <= ty); t = min_pd(ty, tx), which
  // is (ty < tx) ? ty : tx.
  const __mmask8 step_x_first = _mm512_cmp_pd_mask(tx, ty, _CMP_LE_OQ);
  const __mmask8 step_y_first = static_cast<__mmask8>(~step_x_first);
  t = _mm512_min_pd(ty, tx);
  ix = _mm256_mask_add_epi32(ix, step_x_first, ix, RC_LOAD_I(step_x));
  iy = _mm256_mask_add_epi32(iy, step_y_first, iy, RC_LOAD_I(step_y));
  const __m512d new_tx = _mm512_max_pd(_mm512_load_pd(s.exit_limit_x + base),
                                       BoundaryTime(ix, RC_LOAD_I(exit_offset_x), c.r,
                                                    _mm512_load_pd(s.origin_x + base), _mm512_load_pd(s.inv_x + base)));
  const __m512d new_ty = _mm512_max_pd(_mm512_load_pd(s.exit_limit_y + base),
                                       BoundaryTime(iy, RC_LOAD_I(exit_offset_y), c.r,
                                                    _mm512_load_pd(s.origin_y + base), _mm512_load_pd(s.inv_y + base)));
  tx = _mm512_mask_mov_pd(tx, step_x_first, new_tx);
  ty = _mm512_mask_mov_pd(ty, step_y_first, new_ty);
  _mm512_store_pd(s.t_enter + base, t);
  _mm512_store_pd(s.exit_x + base, tx);
  _mm512_store_pd(s.exit_y + base, ty);
  _mm512_store_pd(s.range + base, h.range);
  RC_STORE_I(ix, ix);
  RC_STORE_I(iy, iy);
  RC_STORE_I(nodes, nodes);
  return {static_cast<__mmask8>(~(h.fetch & open)), static_cast<__mmask8>(h.fetch & ~open), h.fetch, h.index};
}

// One pass of CastMarch's loop for the lanes of group g: the sample at
// t = k r, fetched if it is within max range and inside the map.
RC_LANES_TARGET inline StepResult StepMarchGroup(LaneState& s, int g, const Constants& c, const void* cells) {
  const int base = g * kRayLanes;
  const __m256i k = RC_LOAD_I(sample);
  __m256i nodes = RC_LOAD_I(nodes);
  const __m512d t = _mm512_mul_pd(_mm512_cvtepi32_pd(k), c.r);
  const __mmask8 in_range = static_cast<__mmask8>(~_mm256_cmpgt_epi32_mask(k, c.march_samples));
  constexpr int kFloor = _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC;
  const __m256i ix = _mm512_cvttpd_epi32(_mm512_roundscale_pd(
      _mm512_div_pd(_mm512_add_pd(_mm512_load_pd(s.origin_x + base), _mm512_mul_pd(t, _mm512_load_pd(s.dir_x + base))),
                    c.r),
      kFloor));
  const __m256i iy = _mm512_cvttpd_epi32(_mm512_roundscale_pd(
      _mm512_div_pd(_mm512_add_pd(_mm512_load_pd(s.origin_y + base), _mm512_mul_pd(t, _mm512_load_pd(s.dir_y + base))),
                    c.r),
      kFloor));
  const __mmask8 inside = _mm256_cmplt_epu32_mask(ix, c.size_x) & _mm256_cmplt_epu32_mask(iy, c.size_y);
  const __mmask8 fetch = in_range & inside;
  const __m256i index = _mm256_add_epi32(_mm256_mullo_epi32(ix, c.size_y), iy);
  const __m256i cell =
      _mm256_and_si256(_mm256_mmask_i32gather_epi32(_mm256_setzero_si256(), fetch, index, cells, 1), c.byte_mask);
  const __mmask8 open = _mm256_cmpeq_epi32_mask(cell, _mm256_setzero_si256());  // CellState::kFree
  nodes = _mm256_mask_add_epi32(nodes, fetch, nodes, c.one);
  _mm512_store_pd(s.range + base, _mm512_mask_mov_pd(c.max_range, in_range, t));
  RC_STORE_I(sample, _mm256_add_epi32(k, c.one));
  RC_STORE_I(nodes, nodes);
  return {static_cast<__mmask8>(~(fetch & open)), static_cast<__mmask8>(fetch & ~open), fetch, index};
}

// One pass of CastRayMarching's loop for the lanes of group g: both ways
// forward (the jump and the single exact step) computed, one selected.
RC_LANES_TARGET inline StepResult StepRayMarchingGroup(LaneState& s, int g, const Constants& c, const float* field) {
  const int base = g * kRayLanes;
  const __m512d ox = _mm512_load_pd(s.origin_x + base), oy = _mm512_load_pd(s.origin_y + base);
  const __m512d inv_x = _mm512_load_pd(s.inv_x + base), inv_y = _mm512_load_pd(s.inv_y + base);
  const __m512d exit_lim_x = _mm512_load_pd(s.exit_limit_x + base);
  const __m512d exit_lim_y = _mm512_load_pd(s.exit_limit_y + base);
  const __m256i exit_off_x = RC_LOAD_I(exit_offset_x), exit_off_y = RC_LOAD_I(exit_offset_y);
  __m512d t = _mm512_load_pd(s.t_enter + base);
  __m256i ix = RC_LOAD_I(ix), iy = RC_LOAD_I(iy), nodes = RC_LOAD_I(nodes);
  const Head h = LoopHead(t, ix, iy, c.max_range, c.size_x, c.size_y);
  const __m512d d = _mm512_cvtps_pd(_mm256_mmask_i32gather_ps(_mm256_setzero_ps(), h.fetch, h.index, field, 4));
  nodes = _mm256_mask_add_epi32(nodes, h.fetch, nodes, c.one);
  const __mmask8 stops = _mm512_cmp_pd_mask(d, _mm512_setzero_pd(), _CMP_EQ_OQ);
  const __m512d tx = _mm512_max_pd(exit_lim_x, BoundaryTime(ix, exit_off_x, c.r, ox, inv_x));
  const __m512d ty = _mm512_max_pd(exit_lim_y, BoundaryTime(iy, exit_off_y, c.r, oy, inv_y));
  const __m512d t_exit = _mm512_min_pd(ty, tx);  // std::min(tx, ty)
  // The jump from the cell's entry point, and the landing cell's entry and
  // exit times.
  const __m512d jump = _mm512_sub_pd(d, c.jump_margin);
  const __m512d t_land = _mm512_add_pd(t, jump);
  constexpr int kFloor = _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC;
  const __m256i jx = _mm512_cvttpd_epi32(_mm512_roundscale_pd(
      _mm512_div_pd(_mm512_add_pd(ox, _mm512_mul_pd(t_land, _mm512_load_pd(s.dir_x + base))), c.r), kFloor));
  const __m256i jy = _mm512_cvttpd_epi32(_mm512_roundscale_pd(
      _mm512_div_pd(_mm512_add_pd(oy, _mm512_mul_pd(t_land, _mm512_load_pd(s.dir_y + base))), c.r), kFloor));
  const __m512d ex = _mm512_min_pd(_mm512_load_pd(s.entry_limit_x + base),
                                   BoundaryTime(jx, RC_LOAD_I(entry_offset_x), c.r, ox, inv_x));
  const __m512d ey = _mm512_min_pd(_mm512_load_pd(s.entry_limit_y + base),
                                   BoundaryTime(jy, RC_LOAD_I(entry_offset_y), c.r, oy, inv_y));
  const __m512d t_in = _mm512_max_pd(ey, ex);  // std::max(ex, ey)
  const __m512d bx = _mm512_max_pd(exit_lim_x, BoundaryTime(jx, exit_off_x, c.r, ox, inv_x));
  const __m512d by = _mm512_max_pd(exit_lim_y, BoundaryTime(jy, exit_off_y, c.r, oy, inv_y));
  const __m512d t_out = _mm512_min_pd(by, bx);  // std::min(bx, by)
  const __mmask8 jumps = _mm512_cmp_pd_mask(jump, c.r, _CMP_GT_OQ) & _mm512_cmp_pd_mask(t_in, t_out, _CMP_LT_OQ) &
                         _mm512_cmp_pd_mask(t_in, t, _CMP_GT_OQ);
  // Otherwise CastDda's single step (x first on a tie).
  const __mmask8 step_x_first = _mm512_cmp_pd_mask(tx, ty, _CMP_LE_OQ);
  ix = _mm256_mask_add_epi32(ix, step_x_first, ix, RC_LOAD_I(step_x));
  iy = _mm256_mask_add_epi32(iy, static_cast<__mmask8>(~step_x_first), iy, RC_LOAD_I(step_y));
  ix = _mm256_mask_mov_epi32(ix, jumps, jx);
  iy = _mm256_mask_mov_epi32(iy, jumps, jy);
  t = _mm512_mask_mov_pd(t_exit, jumps, t_in);
  _mm512_store_pd(s.t_enter + base, t);
  _mm512_store_pd(s.range + base, h.range);
  RC_STORE_I(ix, ix);
  RC_STORE_I(iy, iy);
  RC_STORE_I(nodes, nodes);
  return {static_cast<__mmask8>(~h.fetch | stops), static_cast<__mmask8>(h.fetch & stops), h.fetch, h.index};
}

// How a recording finds a fetched cell's sector: the sector of byte
// offset + index * element_bytes. Where the fetched structure starts on a
// sector and its cells are a power of two no wider than one, that is
// first + (index >> index_shift), in 32 bits: a shift and an add, where the
// general form takes 64-bit multiplies and a scatter with 64-bit indices
// (several times the cost per step).
struct SectorOfCell {
  bool narrow = false;
  std::int32_t first = 0;
  int index_shift = 0;

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

// Marks the sectors of a group's fetched cells (a recorded batch's touched
// sectors), one scatter for the group (lanes that share a sector write the
// same 1).
RC_LANES_TARGET inline void MarkTouched(const StepResult& step, const LaneRecording& rec, const SectorOfCell& of) {
  if (of.narrow) {
    const __m256i sector =
        _mm256_add_epi32(_mm256_set1_epi32(of.first), _mm256_srl_epi32(step.index, _mm_cvtsi32_si128(of.index_shift)));
    _mm256_mask_i32scatter_epi32(rec.touched, step.fetch, sector, _mm256_set1_epi32(1), 4);
    return;
  }
  const __m512i index = _mm512_cvtepu32_epi64(step.index);
  const __m512i byte = _mm512_add_epi64(_mm512_set1_epi64(static_cast<long long>(rec.offset)),
                                        _mm512_mullo_epi64(index, _mm512_set1_epi64(rec.element_bytes)));
  const __m512i sector = _mm512_srl_epi64(byte, _mm_cvtsi32_si128(rec.sector_shift));
  _mm512_mask_i64scatter_epi32(rec.touched, step.fetch, sector, _mm256_set1_epi32(1), 4);
}

// Appends the indices of group g's fetched cells to their lanes' logs.
RC_LANES_TARGET inline void LogNodes(const StepResult& step, int g, LaneNodeLog& log) {
  alignas(32) std::int32_t index[kRayLanes];
  _mm256_store_si256(reinterpret_cast<__m256i*>(index), step.index);
  for (unsigned m = step.fetch; m != 0; m &= m - 1) {
    const int l = __builtin_ctz(m);
    log.lane[g * kRayLanes + l].push_back(static_cast<std::uint32_t>(index[l]));
  }
}

// Notes where the queries now in `lanes` begin in their lanes' logs.
inline void LogStarts(const LaneState& s, LaneMask lanes, LaneNodeLog& log) {
  for (; lanes != 0; lanes &= lanes - 1) {
    const int l = __builtin_ctzll(lanes);
    log.lane_of[s.query[l]] = static_cast<std::uint32_t>(l);
    log.start_of[s.query[l]] = static_cast<std::uint32_t>(log.lane[l].size());
  }
}

// Every group steps once per round; lanes whose ray ended are refilled.
// Lanes without a query keep stepping harmlessly (every fetch is masked to
// cells inside the map) until the last ray ends; a recording ignores them.
template <RayCastMethod kMethod, bool kRecord>
RC_LANES_TARGET void RunLanes(const RayCastScene& scene, const RayQuery* queries, std::size_t count, RayHit* hits,
                              const Constants& c, const LaneRecording* rec) {
  const void* cells = kMethod != RayCastMethod::kRayMarching ? scene.gather_cells().data() : nullptr;
  const float* field = kMethod == RayCastMethod::kRayMarching ? scene.distance_field()->values().data() : nullptr;
  LaneState s;
  std::size_t next = 0;
  const double r = scene.grid().resolution_m();
  LaneMask live = StartAll(s, queries, count, next, r);
  LaneNodeLog* log = kRecord ? rec->nodes : nullptr;
  // Fetches are masked to cells inside the map.
  const SectorOfCell sector_of =
      kRecord ? SectorOfCell(*rec, scene.grid().cell_count()) : SectorOfCell(LaneRecording{}, 0);
  if (log) {
    for (std::vector<std::uint32_t>& lane : log->lane) lane.clear();
    log->lane_of.assign(count, 0);
    log->start_of.assign(count, 0);
    LogStarts(s, live, *log);
  }
  while (live != 0) {
    LaneMask ended = 0, stopped = 0;
    for (int g = 0; g < kGroups; ++g) {
      const StepResult step = kMethod == RayCastMethod::kDda     ? StepDdaGroup(s, g, c, cells)
                              : kMethod == RayCastMethod::kMarch ? StepMarchGroup(s, g, c, cells)
                                                                 : StepRayMarchingGroup(s, g, c, field);
      ended |= static_cast<LaneMask>(step.ended) << (g * kRayLanes);
      if constexpr (kRecord) {
        stopped |= static_cast<LaneMask>(step.stopped) << (g * kRayLanes);
        // Only the fetches of lanes that hold a query are recorded: a lane
        // whose ray has ended steps on past its end, to cells it never fetched.
        StepResult holding = step;
        holding.fetch &= static_cast<__mmask8>(live >> (g * kRayLanes));
        if (rec->touched) MarkTouched(holding, *rec, sector_of);
        if (log) LogNodes(holding, g, *log);
      }
    }
    ended &= live;
    if constexpr (kRecord) {
      if (rec->last_exits)
        for (LaneMask m = ended; m != 0; m &= m - 1) {
          const int l = __builtin_ctzll(m);
          rec->last_exits[s.query[l]] = s.nodes[l] == 0 ? kNoExit : (stopped >> l) & 1 ? kRayHitReturn : kRayEndReturn;
        }
    }
    if (ended != 0) {
      Refill(s, ended, queries, count, next, live, hits, r);
      if (log) LogStarts(s, ended & live, *log);
    }
  }
}

template <RayCastMethod kMethod>
RC_LANES_TARGET void RunLanes(const RayCastScene& scene, const RayQuery* queries, std::size_t count, RayHit* hits,
                              const Constants& c, const LaneRecording* rec) {
  if (rec)
    RunLanes<kMethod, true>(scene, queries, count, hits, c, rec);
  else
    RunLanes<kMethod, false>(scene, queries, count, hits, c, rec);
}

}  // namespace

bool RayLanesSupported() {
  static const bool supported =
      __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512dq");
  return supported;
}

bool RayLanesApply(const RayCastScene& scene) {
  if (!RayLanesSupported()) return false;
  // Signed 32-bit gather indices, and cell indices computed in 32 bits.
  return scene.grid().cell_count() + RayCastScene::kGatherPadding <=
         static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max());
}

RC_LANES_TARGET void CastRayLanes(const RayCastScene& scene, const RayQuery* queries, std::size_t count,
                                  double max_range_m, RayHit* hits, const LaneRecording* rec) {
  if (count == 0) return;
  const Constants c = MakeConstants(scene.grid(), max_range_m);
  switch (scene.method()) {
    case RayCastMethod::kDda: RunLanes<RayCastMethod::kDda>(scene, queries, count, hits, c, rec); return;
    case RayCastMethod::kMarch:
      // Sample indices are 32-bit in the lanes.
      if (MarchSamples(scene.grid(), max_range_m) < std::numeric_limits<std::int32_t>::max()) {
        RunLanes<RayCastMethod::kMarch>(scene, queries, count, hits, c, rec);
      } else {
        if (rec) throw std::logic_error("CastRayLanes: a recording needs the lanes (RayLanesApply)");
        for (std::size_t i = 0; i < count; ++i)
          hits[i] = CastRay(scene, queries[i].origin_x_m, queries[i].origin_y_m, queries[i].angle_rad, max_range_m);
      }
      return;
    case RayCastMethod::kRayMarching:
      RunLanes<RayCastMethod::kRayMarching>(scene, queries, count, hits, c, rec);
      return;
  }
}

}  // namespace rc

#pragma GCC diagnostic pop

#else  // not x86-64: no lanes; CastRayBatch casts one query at a time.

namespace rc {

bool RayLanesSupported() { return false; }
bool RayLanesApply(const RayCastScene&) { return false; }
void CastRayLanes(const RayCastScene&, const RayQuery*, std::size_t, double, RayHit*, const LaneRecording*) {
  throw std::logic_error("CastRayLanes: AVX-512 lanes exist only on x86-64 (check RayLanesApply first)");
}

}  // namespace rc

#endif
