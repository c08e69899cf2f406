#include "robocore/ray_batch_lanes.h"

// GCC 12 warns of an uninitialized variable inside its own AVX-512 headers
// (the masked forms' _mm512_undefined_pd source); the warning is not ours.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <immintrin.h>

#include <cmath>
#include <cstdint>
#include <limits>

namespace rc {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Per-lane state in memory, between rounds that end a ray. The per-ray
// constants are ray_cast_detail::MakeAxis's values for each axis, plus the
// offsets that turn a cell into the boundary CastRay's Axis::BoundaryTime
// (exit) and EntryTime use, and limits that give a zero direction
// component CastRay's +inf exit and -inf entry: a zero inv_dir makes the
// formula's time +-0, and max(+-0, +inf) = +inf, min(+-0, -inf) = -inf,
// while for step != 0 max(t, -inf) = min(t, +inf) = t.
struct alignas(64) LaneState {
  double origin_x[kRayLanes], origin_y[kRayLanes];
  double dir_x[kRayLanes], dir_y[kRayLanes];
  double inv_x[kRayLanes], inv_y[kRayLanes];
  double exit_limit_x[kRayLanes], exit_limit_y[kRayLanes];
  double entry_limit_x[kRayLanes], entry_limit_y[kRayLanes];
  double t_enter[kRayLanes];
  double exit_x[kRayLanes], exit_y[kRayLanes];  // dda: the current cell's exit times
  double range[kRayLanes];                      // the hit's range if the ray ended this round
  std::int32_t step_x[kRayLanes], step_y[kRayLanes];
  std::int32_t exit_offset_x[kRayLanes], exit_offset_y[kRayLanes];
  std::int32_t entry_offset_x[kRayLanes], entry_offset_y[kRayLanes];
  std::int32_t ix[kRayLanes], iy[kRayLanes];
  std::uint32_t nodes[kRayLanes];
  std::size_t query[kRayLanes];
};

// The scalar Axis::BoundaryTime of CastRay, for a lane's set-up.
double ScalarExitTime(const ray_cast_detail::Axis& a, int cell, double r) { return a.BoundaryTime(cell, r); }

// A ray's set-up in lane l: CastDda's and CastRayMarching's prologue.
void StartLane(LaneState& s, int l, const RayQuery& q, double r, std::size_t query) {
  const ray_cast_detail::Axis ax = ray_cast_detail::MakeAxis(q.origin_x_m, std::cos(q.angle_rad));
  const ray_cast_detail::Axis ay = ray_cast_detail::MakeAxis(q.origin_y_m, std::sin(q.angle_rad));
  s.origin_x[l] = ax.origin;
  s.origin_y[l] = ay.origin;
  s.dir_x[l] = ax.dir;
  s.dir_y[l] = ay.dir;
  s.inv_x[l] = ax.inv_dir;
  s.inv_y[l] = ay.inv_dir;
  s.step_x[l] = ax.step;
  s.step_y[l] = ay.step;
  s.exit_offset_x[l] = ax.step > 0 ? 1 : 0;
  s.exit_offset_y[l] = ay.step > 0 ? 1 : 0;
  s.entry_offset_x[l] = ax.step > 0 ? 0 : 1;
  s.entry_offset_y[l] = ay.step > 0 ? 0 : 1;
  s.exit_limit_x[l] = ax.step == 0 ? kInf : -kInf;
  s.exit_limit_y[l] = ay.step == 0 ? kInf : -kInf;
  s.entry_limit_x[l] = ax.step == 0 ? -kInf : kInf;
  s.entry_limit_y[l] = ay.step == 0 ? -kInf : kInf;
  s.ix[l] = static_cast<int>(std::floor(q.origin_x_m / r));
  s.iy[l] = static_cast<int>(std::floor(q.origin_y_m / r));
  s.t_enter[l] = 0.0;
  s.exit_x[l] = ScalarExitTime(ax, s.ix[l], r);
  s.exit_y[l] = ScalarExitTime(ay, s.iy[l], r);
  s.nodes[l] = 0;
  s.query[l] = query;
}

// Fills every lane (lanes beyond the batch step on a copy of its last query
// and are not live). Returns the live mask.
unsigned StartAllLanes(LaneState& s, const RayQuery* queries, std::size_t count, double r, std::size_t& next) {
  unsigned live = 0;
  for (int l = 0; l < kRayLanes; ++l) {
    const std::size_t q = next < count ? next : count - 1;
    StartLane(s, l, queries[q], r, q);
    if (next < count) {
      live |= 1u << l;
      ++next;
    }
  }
  return live;
}

// Writes the hits of the lanes in `ended` and gives them the next queries;
// lanes left without one leave `live`.
void RefillLanes(LaneState& s, unsigned ended, const RayQuery* queries, std::size_t count, double r,
                 std::size_t& next, unsigned& live, RayHit* hits) {
  while (ended != 0) {
    const int l = __builtin_ctz(ended);
    ended &= ended - 1;
    RayHit& hit = hits[s.query[l]];
    hit.range_m = static_cast<float>(s.range[l]);
    hit.nodes = s.nodes[l];
    if (next < count) {
      StartLane(s, l, queries[next], r, next);
      ++next;
    } else {
      live &= ~(1u << l);
    }
  }
}

#define RC_LANES_TARGET __attribute__((target("avx512f,avx512vl,avx512dq")))

// The vector form of one axis's boundary time, (double(cell + offset) * r -
// origin) * inv, then the limit: max_pd(limit, t) is (t < limit) ? limit : t
// (exit), min_pd(limit, t) is (limit < t) ? limit : t (entry).
RC_LANES_TARGET inline __m512d BoundaryTime(__m256i cell, __m256i offset, __m512d r, __m512d origin,
                                             __m512d inv) {
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

struct Constants {
  __m512d r, max_range;
  __m256i size_x, size_y, one;
};

RC_LANES_TARGET Constants MakeConstants(const OccupancyGrid& g, double max_range) {
  Constants c;
  c.r = _mm512_set1_pd(g.resolution_m());
  c.max_range = _mm512_set1_pd(max_range);
  c.size_x = _mm256_set1_epi32(g.size_x());
  c.size_y = _mm256_set1_epi32(g.size_y());
  c.one = _mm256_set1_epi32(1);
  return c;
}

RC_LANES_TARGET void CastDdaLanes(const RayCastScene& scene, const RayQuery* queries, std::size_t count,
                                  double max_range, RayHit* hits) {
  const OccupancyGrid& g = scene.grid();
  const double r = g.resolution_m();
  const Constants c = MakeConstants(g, max_range);
  const void* cells = scene.gather_cells().data();
  const __m256i byte_mask = _mm256_set1_epi32(0xFF);
  LaneState s;
  std::size_t next = 0;
  unsigned live = StartAllLanes(s, queries, count, r, next);
  while (live != 0) {
    const __m512d ox = _mm512_load_pd(s.origin_x), oy = _mm512_load_pd(s.origin_y);
    const __m512d inv_x = _mm512_load_pd(s.inv_x), inv_y = _mm512_load_pd(s.inv_y);
    const __m512d lim_x = _mm512_load_pd(s.exit_limit_x), lim_y = _mm512_load_pd(s.exit_limit_y);
    const __m256i step_x = _mm256_load_si256(reinterpret_cast<const __m256i*>(s.step_x));
    const __m256i step_y = _mm256_load_si256(reinterpret_cast<const __m256i*>(s.step_y));
    const __m256i off_x = _mm256_load_si256(reinterpret_cast<const __m256i*>(s.exit_offset_x));
    const __m256i off_y = _mm256_load_si256(reinterpret_cast<const __m256i*>(s.exit_offset_y));
    __m512d t = _mm512_load_pd(s.t_enter);
    __m512d tx = _mm512_load_pd(s.exit_x), ty = _mm512_load_pd(s.exit_y);
    __m256i ix = _mm256_load_si256(reinterpret_cast<const __m256i*>(s.ix));
    __m256i iy = _mm256_load_si256(reinterpret_cast<const __m256i*>(s.iy));
    __m256i nodes = _mm256_load_si256(reinterpret_cast<const __m256i*>(s.nodes));
    __mmask8 ended;
    __m512d range;
    while (true) {
      const Head h = LoopHead(t, ix, iy, c.max_range, c.size_x, c.size_y);
      const __m256i cell = _mm256_and_si256(
          _mm256_mmask_i32gather_epi32(_mm256_setzero_si256(), h.fetch, h.index, cells, 1), byte_mask);
      const __mmask8 open = _mm256_cmpeq_epi32_mask(cell, _mm256_setzero_si256());  // CellState::kFree
      nodes = _mm256_mask_add_epi32(nodes, h.fetch, nodes, c.one);
      ended = static_cast<__mmask8>(~(h.fetch & open)) & static_cast<__mmask8>(live);
      range = h.range;
      // CastDda's step: x first on a tie (tx <= ty), t = min_pd(ty, tx),
      // which is (ty < tx) ? ty : tx.
      const __mmask8 step_x_first = _mm512_cmp_pd_mask(tx, ty, _CMP_LE_OQ);
      t = _mm512_min_pd(ty, tx);
      ix = _mm256_mask_add_epi32(ix, step_x_first, ix, step_x);
      iy = _mm256_mask_add_epi32(iy, static_cast<__mmask8>(~step_x_first), iy, step_y);
      tx = _mm512_mask_mov_pd(tx, step_x_first, _mm512_max_pd(lim_x, BoundaryTime(ix, off_x, c.r, ox, inv_x)));
      ty = _mm512_mask_mov_pd(ty, static_cast<__mmask8>(~step_x_first),
                              _mm512_max_pd(lim_y, BoundaryTime(iy, off_y, c.r, oy, inv_y)));
      if (ended != 0) break;
    }
    _mm512_store_pd(s.t_enter, t);
    _mm512_store_pd(s.exit_x, tx);
    _mm512_store_pd(s.exit_y, ty);
    _mm512_store_pd(s.range, range);
    _mm256_store_si256(reinterpret_cast<__m256i*>(s.ix), ix);
    _mm256_store_si256(reinterpret_cast<__m256i*>(s.iy), iy);
    _mm256_store_si256(reinterpret_cast<__m256i*>(s.nodes), nodes);
    RefillLanes(s, ended, queries, count, r, next, live, hits);
  }
}

RC_LANES_TARGET void CastRayMarchingLanes(const RayCastScene& scene, const RayQuery* queries, std::size_t count,
                                          double max_range, RayHit* hits) {
  const OccupancyGrid& g = scene.grid();
  const double r = g.resolution_m();
  const Constants c = MakeConstants(g, max_range);
  const float* field = scene.distance_field()->values().data();
  // CastRayMarching's margin, computed as it computes it.
  const __m512d margin = _mm512_set1_pd((std::sqrt(2.0) + 0.5) * r);
  LaneState s;
  std::size_t next = 0;
  unsigned live = StartAllLanes(s, queries, count, r, next);
  while (live != 0) {
    const __m512d ox = _mm512_load_pd(s.origin_x), oy = _mm512_load_pd(s.origin_y);
    const __m512d dx = _mm512_load_pd(s.dir_x), dy = _mm512_load_pd(s.dir_y);
    const __m512d inv_x = _mm512_load_pd(s.inv_x), inv_y = _mm512_load_pd(s.inv_y);
    const __m512d exit_lim_x = _mm512_load_pd(s.exit_limit_x), exit_lim_y = _mm512_load_pd(s.exit_limit_y);
    const __m512d entry_lim_x = _mm512_load_pd(s.entry_limit_x), entry_lim_y = _mm512_load_pd(s.entry_limit_y);
    const __m256i step_x = _mm256_load_si256(reinterpret_cast<const __m256i*>(s.step_x));
    const __m256i step_y = _mm256_load_si256(reinterpret_cast<const __m256i*>(s.step_y));
    const __m256i exit_off_x = _mm256_load_si256(reinterpret_cast<const __m256i*>(s.exit_offset_x));
    const __m256i exit_off_y = _mm256_load_si256(reinterpret_cast<const __m256i*>(s.exit_offset_y));
    const __m256i entry_off_x = _mm256_load_si256(reinterpret_cast<const __m256i*>(s.entry_offset_x));
    const __m256i entry_off_y = _mm256_load_si256(reinterpret_cast<const __m256i*>(s.entry_offset_y));
    __m512d t = _mm512_load_pd(s.t_enter);
    __m256i ix = _mm256_load_si256(reinterpret_cast<const __m256i*>(s.ix));
    __m256i iy = _mm256_load_si256(reinterpret_cast<const __m256i*>(s.iy));
    __m256i nodes = _mm256_load_si256(reinterpret_cast<const __m256i*>(s.nodes));
    __mmask8 ended;
    __m512d range;
    while (true) {
      const Head h = LoopHead(t, ix, iy, c.max_range, c.size_x, c.size_y);
      const __m512d d =
          _mm512_cvtps_pd(_mm256_mmask_i32gather_ps(_mm256_setzero_ps(), h.fetch, h.index, field, 4));
      nodes = _mm256_mask_add_epi32(nodes, h.fetch, nodes, c.one);
      const __mmask8 stops = _mm512_cmp_pd_mask(d, _mm512_setzero_pd(), _CMP_EQ_OQ);
      ended = static_cast<__mmask8>(~h.fetch | stops) & static_cast<__mmask8>(live);
      range = h.range;
      const __m512d tx = _mm512_max_pd(exit_lim_x, BoundaryTime(ix, exit_off_x, c.r, ox, inv_x));
      const __m512d ty = _mm512_max_pd(exit_lim_y, BoundaryTime(iy, exit_off_y, c.r, oy, inv_y));
      const __m512d t_exit = _mm512_min_pd(ty, tx);  // std::min(tx, ty)
      // The jump from the cell's entry point, and the landing cell's
      // entry and exit times.
      const __m512d jump = _mm512_sub_pd(d, margin);
      const __m512d t_land = _mm512_add_pd(t, jump);
      constexpr int kFloor = _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC;
      const __m256i jx = _mm512_cvttpd_epi32(
          _mm512_roundscale_pd(_mm512_div_pd(_mm512_add_pd(ox, _mm512_mul_pd(t_land, dx)), c.r), kFloor));
      const __m256i jy = _mm512_cvttpd_epi32(
          _mm512_roundscale_pd(_mm512_div_pd(_mm512_add_pd(oy, _mm512_mul_pd(t_land, dy)), c.r), kFloor));
      const __m512d ex = _mm512_min_pd(entry_lim_x, BoundaryTime(jx, entry_off_x, c.r, ox, inv_x));
      const __m512d ey = _mm512_min_pd(entry_lim_y, BoundaryTime(jy, entry_off_y, c.r, oy, inv_y));
      const __m512d t_in = _mm512_max_pd(ey, ex);  // std::max(ex, ey)
      const __m512d bx = _mm512_max_pd(exit_lim_x, BoundaryTime(jx, exit_off_x, c.r, ox, inv_x));
      const __m512d by = _mm512_max_pd(exit_lim_y, BoundaryTime(jy, exit_off_y, c.r, oy, inv_y));
      const __m512d t_out = _mm512_min_pd(by, bx);  // std::min(bx, by)
      const __mmask8 jumps = _mm512_cmp_pd_mask(jump, c.r, _CMP_GT_OQ) &
                             _mm512_cmp_pd_mask(t_in, t_out, _CMP_LT_OQ) &
                             _mm512_cmp_pd_mask(t_in, t, _CMP_GT_OQ);
      // Otherwise CastDda's single step (x first on a tie).
      const __mmask8 step_x_first = _mm512_cmp_pd_mask(tx, ty, _CMP_LE_OQ);
      ix = _mm256_mask_add_epi32(ix, step_x_first, ix, step_x);
      iy = _mm256_mask_add_epi32(iy, static_cast<__mmask8>(~step_x_first), iy, step_y);
      ix = _mm256_mask_mov_epi32(ix, jumps, jx);
      iy = _mm256_mask_mov_epi32(iy, jumps, jy);
      t = _mm512_mask_mov_pd(t_exit, jumps, t_in);
      if (ended != 0) break;
    }
    _mm512_store_pd(s.t_enter, t);
    _mm512_store_pd(s.range, range);
    _mm256_store_si256(reinterpret_cast<__m256i*>(s.ix), ix);
    _mm256_store_si256(reinterpret_cast<__m256i*>(s.iy), iy);
    _mm256_store_si256(reinterpret_cast<__m256i*>(s.nodes), nodes);
    RefillLanes(s, ended, queries, count, r, next, live, hits);
  }
}

}  // namespace

bool RayLanesSupported() {
  static const bool supported = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
                                __builtin_cpu_supports("avx512dq");
  return supported;
}

bool RayLanesApply(const RayCastScene& scene) {
  if (!RayLanesSupported()) return false;
  if (scene.method() != RayCastMethod::kDda && scene.method() != RayCastMethod::kRayMarching) return false;
  // Signed 32-bit gather indices, and cell indices computed in 32 bits.
  return scene.grid().cell_count() + RayCastScene::kGatherPadding <=
         static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max());
}

void CastRayLanes(const RayCastScene& scene, const RayQuery* queries, std::size_t count, double max_range_m,
                  RayHit* hits) {
  if (count == 0) return;
  if (scene.method() == RayCastMethod::kDda)
    CastDdaLanes(scene, queries, count, max_range_m, hits);
  else
    CastRayMarchingLanes(scene, queries, count, max_range_m, hits);
}

}  // namespace rc

#pragma GCC diagnostic pop
