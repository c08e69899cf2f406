// The lane kernels in AVX-512 (F, VL, DQ): four groups of eight rays, one
// __m512d of doubles per group, every per-step decision a __mmask8, every
// group's cell fetches one gather. The contract (bit-identical hits) and
// the reasons are in ray_batch_lanes.h; the shared state and loop in
// ray_lane_state.h and ray_lane_loop.inc.
#include "robocore/ray_lane_state.h"

#if defined(__x86_64__)
// GCC 12 warns of an uninitialized variable inside its own AVX-512 headers
// (the masked forms' _mm512_undefined_pd source); the warning is not ours.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"
#include <immintrin.h>

#include <vector>

namespace rc::ray_lanes {
namespace {

#define RC_LANES_TARGET __attribute__((target("avx512f,avx512vl,avx512dq")))

// The vector form of one axis's boundary time, (double(cell + offset) * r -
// origin) * inv, then the limit: max_pd(limit, t) is (t < limit) ? limit : t
// (exit), min_pd(limit, t) is (limit < t) ? limit : t (entry).
RC_LANES_TARGET inline __m512d BoundaryTime(__m256i cell, __m256i offset, __m512d r, __m512d origin, __m512d inv) {
  const __m512d b = _mm512_cvtepi32_pd(_mm256_add_epi32(cell, offset));
  return _mm512_mul_pd(_mm512_sub_pd(_mm512_mul_pd(b, r), origin), inv);
}

// floor(x) for the cell of a point (CastMarch's and CastRayMarching's
// static_cast<int>(std::floor(...)); out of int range both give INT_MIN).
RC_LANES_TARGET inline __m256i FloorToCell(__m512d x) {
  constexpr int kFloor = _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC;
  return _mm512_cvttpd_epi32(_mm512_roundscale_pd(x, kFloor));
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

// What one pass of a group did (RunLaneLoop's StepResult), with the cell
// indices of the lanes that fetched.
struct StepResult {
  __mmask8 ended, stopped, fetch;
  __m256i index;
};

#define RC_LOAD_I(field) _mm256_load_si256(reinterpret_cast<const __m256i*>(s.field + base))
#define RC_STORE_I(field, v) _mm256_store_si256(reinterpret_cast<__m256i*>(s.field + base), v)

class Avx512Kernel {
 public:
  static constexpr int kWidth = 8;

  RC_LANES_TARGET Avx512Kernel(const LaneScene& scene, const LaneRecording* rec)
      : cells_(scene.cells), field_(scene.field) {
    r_ = _mm512_set1_pd(scene.r);
    max_range_ = _mm512_set1_pd(scene.max_range);
    jump_margin_ = _mm512_set1_pd(scene.jump_margin);
    size_x_ = _mm256_set1_epi32(scene.size_x);
    size_y_ = _mm256_set1_epi32(scene.size_y);
    one_ = _mm256_set1_epi32(1);
    byte_mask_ = _mm256_set1_epi32(0xFF);
    march_samples_ = _mm256_set1_epi32(scene.march_samples);
    // Fetches are masked to cells inside the map.
    if (rec) sector_of_ = SectorOfCell(*rec, scene.cell_count);
  }

  template <RayCastMethod kMethod>
  RC_LANES_TARGET StepResult Step(LaneState& s, int g) const {
    if constexpr (kMethod == RayCastMethod::kDda) return StepDda(s, g);
    if constexpr (kMethod == RayCastMethod::kMarch) return StepMarch(s, g);
    if constexpr (kMethod == RayCastMethod::kRayMarching) return StepRayMarching(s, g);
  }

  // Marks the sectors of a group's fetched cells (a recorded batch's touched
  // sectors), one scatter for the group (lanes that share a sector write the
  // same 1), and logs their nodes.
  RC_LANES_TARGET void Record(const StepResult& step, unsigned fetch, int first, const LaneRecording& rec) const {
    const __mmask8 m = static_cast<__mmask8>(fetch);
    if (rec.touched) {
      if (sector_of_.narrow) {
        const __m256i sector =
            _mm256_add_epi32(_mm256_set1_epi32(sector_of_.first),
                             _mm256_srl_epi32(step.index, _mm_cvtsi32_si128(sector_of_.index_shift)));
        _mm256_mask_i32scatter_epi32(rec.touched, m, sector, _mm256_set1_epi32(1), 4);
      } else {
        const __m512i index = _mm512_cvtepu32_epi64(step.index);
        const __m512i byte = _mm512_add_epi64(_mm512_set1_epi64(static_cast<long long>(rec.offset)),
                                              _mm512_mullo_epi64(index, _mm512_set1_epi64(rec.element_bytes)));
        const __m512i sector = _mm512_srl_epi64(byte, _mm_cvtsi32_si128(rec.sector_shift));
        _mm512_mask_i64scatter_epi32(rec.touched, m, sector, _mm256_set1_epi32(1), 4);
      }
    }
    if (rec.nodes) {
      alignas(32) std::int32_t index[kWidth];
      _mm256_store_si256(reinterpret_cast<__m256i*>(index), step.index);
      LogNodes(index, fetch, first, *rec.nodes);
    }
  }

 private:
  RC_LANES_TARGET Head LoopHead(__m512d t, __m256i ix, __m256i iy) const {
    Head h;
    const __mmask8 in_range = _mm512_cmp_pd_mask(t, max_range_, _CMP_LT_OQ);
    const __mmask8 inside = _mm256_cmplt_epu32_mask(ix, size_x_) & _mm256_cmplt_epu32_mask(iy, size_y_);
    h.fetch = in_range & inside;
    h.index = _mm256_add_epi32(_mm256_mullo_epi32(ix, size_y_), iy);
    h.range = _mm512_min_pd(max_range_, t);
    return h;
  }

  // The cell states of the fetching lanes (0 elsewhere): a 32-bit gather of
  // the byte at each index (the gather cells are padded for it), masked.
  RC_LANES_TARGET __m256i GatherCells(__mmask8 fetch, __m256i index) const {
    return _mm256_and_si256(_mm256_mmask_i32gather_epi32(_mm256_setzero_si256(), fetch, index, cells_, 1), byte_mask_);
  }

  // One pass of CastDda's loop for the lanes of group g.
  RC_LANES_TARGET StepResult StepDda(LaneState& s, int g) const {
    const int base = g * kWidth;
    __m512d t = _mm512_load_pd(s.t_enter + base);
    __m512d tx = _mm512_load_pd(s.exit_x + base), ty = _mm512_load_pd(s.exit_y + base);
    __m256i ix = RC_LOAD_I(ix), iy = RC_LOAD_I(iy), nodes = RC_LOAD_I(nodes);
    const Head h = LoopHead(t, ix, iy);
    const __m256i cell = GatherCells(h.fetch, h.index);
    const __mmask8 open = _mm256_cmpeq_epi32_mask(cell, _mm256_setzero_si256());  // CellState::kFree
    nodes = _mm256_mask_add_epi32(nodes, h.fetch, nodes, one_);
    // CastDda's step: x first on a tie (tx <= ty); t = min_pd(ty, tx), which
    // is (ty < tx) ? ty : tx.
    const __mmask8 step_x_first = _mm512_cmp_pd_mask(tx, ty, _CMP_LE_OQ);
    const __mmask8 step_y_first = static_cast<__mmask8>(~step_x_first);
    t = _mm512_min_pd(ty, tx);
    ix = _mm256_mask_add_epi32(ix, step_x_first, ix, RC_LOAD_I(step_x));
    iy = _mm256_mask_add_epi32(iy, step_y_first, iy, RC_LOAD_I(step_y));
    const __m512d new_tx =
        _mm512_max_pd(_mm512_load_pd(s.exit_limit_x + base),
                      BoundaryTime(ix, RC_LOAD_I(exit_offset_x), r_, _mm512_load_pd(s.origin_x + base),
                                   _mm512_load_pd(s.inv_x + base)));
    const __m512d new_ty =
        _mm512_max_pd(_mm512_load_pd(s.exit_limit_y + base),
                      BoundaryTime(iy, RC_LOAD_I(exit_offset_y), r_, _mm512_load_pd(s.origin_y + base),
                                   _mm512_load_pd(s.inv_y + base)));
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
  RC_LANES_TARGET StepResult StepMarch(LaneState& s, int g) const {
    const int base = g * kWidth;
    const __m256i k = RC_LOAD_I(sample);
    __m256i nodes = RC_LOAD_I(nodes);
    const __m512d t = _mm512_mul_pd(_mm512_cvtepi32_pd(k), r_);
    const __mmask8 in_range = static_cast<__mmask8>(~_mm256_cmpgt_epi32_mask(k, march_samples_));
    const __m256i ix = FloorToCell(_mm512_div_pd(
        _mm512_add_pd(_mm512_load_pd(s.origin_x + base), _mm512_mul_pd(t, _mm512_load_pd(s.dir_x + base))), r_));
    const __m256i iy = FloorToCell(_mm512_div_pd(
        _mm512_add_pd(_mm512_load_pd(s.origin_y + base), _mm512_mul_pd(t, _mm512_load_pd(s.dir_y + base))), r_));
    const __mmask8 inside = _mm256_cmplt_epu32_mask(ix, size_x_) & _mm256_cmplt_epu32_mask(iy, size_y_);
    const __mmask8 fetch = in_range & inside;
    const __m256i index = _mm256_add_epi32(_mm256_mullo_epi32(ix, size_y_), iy);
    const __m256i cell = GatherCells(fetch, index);
    const __mmask8 open = _mm256_cmpeq_epi32_mask(cell, _mm256_setzero_si256());  // CellState::kFree
    nodes = _mm256_mask_add_epi32(nodes, fetch, nodes, one_);
    _mm512_store_pd(s.range + base, _mm512_mask_mov_pd(max_range_, in_range, t));
    RC_STORE_I(sample, _mm256_add_epi32(k, one_));
    RC_STORE_I(nodes, nodes);
    return {static_cast<__mmask8>(~(fetch & open)), static_cast<__mmask8>(fetch & ~open), fetch, index};
  }

  // One pass of CastRayMarching's loop for the lanes of group g: both ways
  // forward (the jump and the single exact step) computed, one selected.
  RC_LANES_TARGET StepResult StepRayMarching(LaneState& s, int g) const {
    const int base = g * kWidth;
    const __m512d ox = _mm512_load_pd(s.origin_x + base), oy = _mm512_load_pd(s.origin_y + base);
    const __m512d inv_x = _mm512_load_pd(s.inv_x + base), inv_y = _mm512_load_pd(s.inv_y + base);
    const __m512d exit_lim_x = _mm512_load_pd(s.exit_limit_x + base);
    const __m512d exit_lim_y = _mm512_load_pd(s.exit_limit_y + base);
    const __m256i exit_off_x = RC_LOAD_I(exit_offset_x), exit_off_y = RC_LOAD_I(exit_offset_y);
    __m512d t = _mm512_load_pd(s.t_enter + base);
    __m256i ix = RC_LOAD_I(ix), iy = RC_LOAD_I(iy), nodes = RC_LOAD_I(nodes);
    const Head h = LoopHead(t, ix, iy);
    const __m512d d = _mm512_cvtps_pd(_mm256_mmask_i32gather_ps(_mm256_setzero_ps(), h.fetch, h.index, field_, 4));
    nodes = _mm256_mask_add_epi32(nodes, h.fetch, nodes, one_);
    const __mmask8 stops = _mm512_cmp_pd_mask(d, _mm512_setzero_pd(), _CMP_EQ_OQ);
    const __m512d tx = _mm512_max_pd(exit_lim_x, BoundaryTime(ix, exit_off_x, r_, ox, inv_x));
    const __m512d ty = _mm512_max_pd(exit_lim_y, BoundaryTime(iy, exit_off_y, r_, oy, inv_y));
    const __m512d t_exit = _mm512_min_pd(ty, tx);  // std::min(tx, ty)
    // The jump from the cell's entry point, and the landing cell's entry and
    // exit times.
    const __m512d jump = _mm512_sub_pd(d, jump_margin_);
    const __m512d t_land = _mm512_add_pd(t, jump);
    const __m256i jx =
        FloorToCell(_mm512_div_pd(_mm512_add_pd(ox, _mm512_mul_pd(t_land, _mm512_load_pd(s.dir_x + base))), r_));
    const __m256i jy =
        FloorToCell(_mm512_div_pd(_mm512_add_pd(oy, _mm512_mul_pd(t_land, _mm512_load_pd(s.dir_y + base))), r_));
    const __m512d ex = _mm512_min_pd(_mm512_load_pd(s.entry_limit_x + base),
                                     BoundaryTime(jx, RC_LOAD_I(entry_offset_x), r_, ox, inv_x));
    const __m512d ey = _mm512_min_pd(_mm512_load_pd(s.entry_limit_y + base),
                                     BoundaryTime(jy, RC_LOAD_I(entry_offset_y), r_, oy, inv_y));
    const __m512d t_in = _mm512_max_pd(ey, ex);  // std::max(ex, ey)
    const __m512d bx = _mm512_max_pd(exit_lim_x, BoundaryTime(jx, exit_off_x, r_, ox, inv_x));
    const __m512d by = _mm512_max_pd(exit_lim_y, BoundaryTime(jy, exit_off_y, r_, oy, inv_y));
    const __m512d t_out = _mm512_min_pd(by, bx);  // std::min(bx, by)
    const __mmask8 jumps = _mm512_cmp_pd_mask(jump, r_, _CMP_GT_OQ) & _mm512_cmp_pd_mask(t_in, t_out, _CMP_LT_OQ) &
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

  const void* cells_;
  const float* field_;
  __m512d r_, max_range_, jump_margin_;
  __m256i size_x_, size_y_, one_, byte_mask_;
  __m256i march_samples_;
  SectorOfCell sector_of_;
};

#undef RC_LOAD_I
#undef RC_STORE_I

#include "robocore/ray_lane_loop.inc"

}  // namespace

RC_LANES_TARGET void CastLanesAvx512(RayCastMethod method, const LaneScene& scene, const RayQuery* queries,
                                     std::size_t count, RayHit* hits, const LaneRecording* recording) {
  const Avx512Kernel kernel(scene, recording);
  RunLanes(method, kernel, scene, queries, count, hits, recording);
}

}  // namespace rc::ray_lanes

#pragma GCC diagnostic pop

#else  // not x86-64: never called (RayLanesApply is false).

#include <stdexcept>

namespace rc::ray_lanes {

void CastLanesAvx512(RayCastMethod, const LaneScene&, const RayQuery*, std::size_t, RayHit*, const LaneRecording*) {
  throw std::logic_error("CastLanesAvx512: AVX-512 exists only on x86-64");
}

}  // namespace rc::ray_lanes

#endif
