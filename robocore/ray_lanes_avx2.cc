// The lane kernels in AVX2, for CPUs without AVX-512: eight groups of four
// rays, one __m256d of doubles per group. The steps are ray_lanes_avx512.cc's
// operations in the same order on the same values; what AVX-512 does with a
// mask register is done here with a vector of all-ones lanes (32-bit for
// cells and indices, 64-bit for times) and blends, which select exactly as
// the masked moves do. AVX2 has no scatter: a recording marks sectors with
// a store per lane. The contract (bit-identical hits) is in
// ray_batch_lanes.h; the shared state and loop in ray_lane_state.h and
// ray_lane_loop.inc.
//
// The three steps mirror ray_lanes_avx512.cc's line for line, so that each
// can be read against the other and against the scalar kernel. Writing them
// once over a small vector-traits layer would remove the mirror; that waits
// for a host where the AVX-512 form can be run and timed, since it would
// rewrite the AVX-512 steps too.
#include "robocore/ray_lane_state.h"

#if defined(__x86_64__)
#include <immintrin.h>

#include <vector>

namespace rc::ray_lanes {
namespace {

#define RC_LANES_TARGET __attribute__((target("avx2")))

// A 32-bit lane mask widened to the 64-bit lanes of doubles (sign extension
// keeps all-ones all-ones), and a 64-bit mask narrowed to 32-bit lanes (the
// low half of each).
RC_LANES_TARGET inline __m256d Widen(__m128i mask) { return _mm256_castsi256_pd(_mm256_cvtepi32_epi64(mask)); }
RC_LANES_TARGET inline __m128i Narrow(__m256d mask) {
  const __m256i low_halves = _mm256_setr_epi32(0, 2, 4, 6, 1, 3, 5, 7);
  return _mm256_castsi256_si128(_mm256_permutevar8x32_epi32(_mm256_castpd_si256(mask), low_halves));
}
// Bit i set where lane i of the mask is set.
RC_LANES_TARGET inline unsigned Bits(__m128i mask) {
  return static_cast<unsigned>(_mm_movemask_ps(_mm_castsi128_ps(mask)));
}

// The vector form of one axis's boundary time, (double(cell + offset) * r -
// origin) * inv (the limit is applied by the caller, as in the AVX-512 form).
RC_LANES_TARGET inline __m256d BoundaryTime(__m128i cell, __m128i offset, __m256d r, __m256d origin, __m256d inv) {
  const __m256d b = _mm256_cvtepi32_pd(_mm_add_epi32(cell, offset));
  return _mm256_mul_pd(_mm256_sub_pd(_mm256_mul_pd(b, r), origin), inv);
}

// floor(x) for the cell of a point; out of int range gives INT_MIN, as the
// AVX-512 conversion does.
RC_LANES_TARGET inline __m128i FloorToCell(__m256d x) {
  return _mm256_cvttpd_epi32(_mm256_round_pd(x, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC));
}

// The head of a loop pass (ray_lanes_avx512.cc's LoopHead), masks as
// 32-bit lanes.
struct Head {
  __m128i fetch;
  __m128i index;
  __m256d range;
};

// What one pass of a group did (RunLaneLoop's StepResult), with the cell
// indices of the lanes that fetched.
struct StepResult {
  unsigned ended, stopped, fetch;
  __m128i index;
};

#define RC_LOAD_I(field) _mm_load_si128(reinterpret_cast<const __m128i*>(s.field + base))
#define RC_STORE_I(field, v) _mm_store_si128(reinterpret_cast<__m128i*>(s.field + base), v)

class Avx2Kernel {
 public:
  static constexpr int kWidth = 4;

  RC_LANES_TARGET Avx2Kernel(const LaneScene& scene, const LaneRecording* rec)
      : cells_(scene.cells), field_(scene.field) {
    r_ = _mm256_set1_pd(scene.r);
    max_range_ = _mm256_set1_pd(scene.max_range);
    jump_margin_ = _mm256_set1_pd(scene.jump_margin);
    // Unsigned 32-bit compares as signed ones with the sign bit flipped.
    sign_ = _mm_set1_epi32(static_cast<int>(0x80000000u));
    size_x_biased_ = _mm_xor_si128(_mm_set1_epi32(scene.size_x), sign_);
    size_y_ = _mm_set1_epi32(scene.size_y);
    size_y_biased_ = _mm_xor_si128(size_y_, sign_);
    byte_mask_ = _mm_set1_epi32(0xFF);
    march_samples_ = _mm_set1_epi32(scene.march_samples);
    lane_bits_ = _mm_setr_epi32(1, 2, 4, 8);
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
  // sectors) and logs their nodes. Where a sector is first + (index >>
  // shift) (SectorOfCell), every lane stores: one that did not fetch stores
  // the first fetching lane's 1 again, so there is no branch per lane (the
  // fetch pattern is not predictable); elsewhere one lane at a time.
  RC_LANES_TARGET void Record(const StepResult& step, unsigned fetch, int first, const LaneRecording& rec) const {
    if (fetch == 0) return;
    alignas(16) std::int32_t index[kWidth];
    if (rec.nodes || !sector_of_.narrow) _mm_store_si128(reinterpret_cast<__m128i*>(index), step.index);
    if (rec.touched) {
      if (sector_of_.narrow) {
        const __m128i sector = _mm_add_epi32(_mm_set1_epi32(sector_of_.first),
                                             _mm_srl_epi32(step.index, _mm_cvtsi32_si128(sector_of_.index_shift)));
        const __m128i lead =
            _mm_castps_si128(_mm_permutevar_ps(_mm_castsi128_ps(sector), _mm_set1_epi32(__builtin_ctz(fetch))));
        const __m128i fetched =
            _mm_cmpeq_epi32(_mm_and_si128(_mm_set1_epi32(static_cast<int>(fetch)), lane_bits_), lane_bits_);
        alignas(16) std::int32_t at[kWidth];
        _mm_store_si128(reinterpret_cast<__m128i*>(at), _mm_blendv_epi8(lead, sector, fetched));
        for (int i = 0; i < kWidth; ++i) rec.touched[at[i]] = 1;
      } else {
        for (unsigned m = fetch; m != 0; m &= m - 1) {
          const std::uint32_t cell = static_cast<std::uint32_t>(index[__builtin_ctz(m)]);
          rec.touched[(rec.offset + std::uint64_t{cell} * rec.element_bytes) >> rec.sector_shift] = 1;
        }
      }
    }
    if (rec.nodes) LogNodes(index, fetch, first, *rec.nodes);
  }

 private:
  RC_LANES_TARGET __m128i Inside(__m128i ix, __m128i iy) const {
    return _mm_and_si128(_mm_cmplt_epi32(_mm_xor_si128(ix, sign_), size_x_biased_),
                         _mm_cmplt_epi32(_mm_xor_si128(iy, sign_), size_y_biased_));
  }

  RC_LANES_TARGET Head LoopHead(__m256d t, __m128i ix, __m128i iy) const {
    Head h;
    const __m128i in_range = Narrow(_mm256_cmp_pd(t, max_range_, _CMP_LT_OQ));
    h.fetch = _mm_and_si128(in_range, Inside(ix, iy));
    h.index = _mm_add_epi32(_mm_mullo_epi32(ix, size_y_), iy);
    h.range = _mm256_min_pd(max_range_, t);
    return h;
  }

  // The cell states of the fetching lanes (0 elsewhere): a 32-bit gather of
  // the byte at each index (the gather cells are padded for it), masked.
  RC_LANES_TARGET __m128i GatherCells(__m128i fetch, __m128i index) const {
    const __m128i words =
        _mm_mask_i32gather_epi32(_mm_setzero_si128(), static_cast<const int*>(cells_), index, fetch, 1);
    return _mm_and_si128(words, byte_mask_);
  }

  // One pass of CastDda's loop for the lanes of group g.
  RC_LANES_TARGET StepResult StepDda(LaneState& s, int g) const {
    const int base = g * kWidth;
    __m256d t = _mm256_load_pd(s.t_enter + base);
    __m256d tx = _mm256_load_pd(s.exit_x + base), ty = _mm256_load_pd(s.exit_y + base);
    __m128i ix = RC_LOAD_I(ix), iy = RC_LOAD_I(iy), nodes = RC_LOAD_I(nodes);
    const Head h = LoopHead(t, ix, iy);
    const __m128i open = _mm_cmpeq_epi32(GatherCells(h.fetch, h.index), _mm_setzero_si128());  // CellState::kFree
    nodes = _mm_sub_epi32(nodes, h.fetch);                                                     // + 1 where fetched
    // CastDda's step: x first on a tie (tx <= ty); t = min_pd(ty, tx).
    const __m256d step_x_first = _mm256_cmp_pd(tx, ty, _CMP_LE_OQ);
    const __m128i step_x_first_i = Narrow(step_x_first);
    t = _mm256_min_pd(ty, tx);
    ix = _mm_add_epi32(ix, _mm_and_si128(step_x_first_i, RC_LOAD_I(step_x)));
    iy = _mm_add_epi32(iy, _mm_andnot_si128(step_x_first_i, RC_LOAD_I(step_y)));
    const __m256d new_tx =
        _mm256_max_pd(_mm256_load_pd(s.exit_limit_x + base),
                      BoundaryTime(ix, RC_LOAD_I(exit_offset_x), r_, _mm256_load_pd(s.origin_x + base),
                                   _mm256_load_pd(s.inv_x + base)));
    const __m256d new_ty =
        _mm256_max_pd(_mm256_load_pd(s.exit_limit_y + base),
                      BoundaryTime(iy, RC_LOAD_I(exit_offset_y), r_, _mm256_load_pd(s.origin_y + base),
                                   _mm256_load_pd(s.inv_y + base)));
    tx = _mm256_blendv_pd(tx, new_tx, step_x_first);
    ty = _mm256_blendv_pd(new_ty, ty, step_x_first);
    _mm256_store_pd(s.t_enter + base, t);
    _mm256_store_pd(s.exit_x + base, tx);
    _mm256_store_pd(s.exit_y + base, ty);
    _mm256_store_pd(s.range + base, h.range);
    RC_STORE_I(ix, ix);
    RC_STORE_I(iy, iy);
    RC_STORE_I(nodes, nodes);
    const unsigned fetch = Bits(h.fetch), free = Bits(open);
    return {~(fetch & free) & 0xFu, fetch & ~free, fetch, h.index};
  }

  // One pass of CastMarch's loop for the lanes of group g: the sample at
  // t = k r, fetched if it is within max range and inside the map.
  RC_LANES_TARGET StepResult StepMarch(LaneState& s, int g) const {
    const int base = g * kWidth;
    const __m128i k = RC_LOAD_I(sample);
    __m128i nodes = RC_LOAD_I(nodes);
    const __m256d t = _mm256_mul_pd(_mm256_cvtepi32_pd(k), r_);
    const __m128i beyond = _mm_cmpgt_epi32(k, march_samples_);
    const __m128i ix = FloorToCell(_mm256_div_pd(
        _mm256_add_pd(_mm256_load_pd(s.origin_x + base), _mm256_mul_pd(t, _mm256_load_pd(s.dir_x + base))), r_));
    const __m128i iy = FloorToCell(_mm256_div_pd(
        _mm256_add_pd(_mm256_load_pd(s.origin_y + base), _mm256_mul_pd(t, _mm256_load_pd(s.dir_y + base))), r_));
    const __m128i fetch = _mm_andnot_si128(beyond, Inside(ix, iy));
    const __m128i index = _mm_add_epi32(_mm_mullo_epi32(ix, size_y_), iy);
    const __m128i open = _mm_cmpeq_epi32(GatherCells(fetch, index), _mm_setzero_si128());  // CellState::kFree
    nodes = _mm_sub_epi32(nodes, fetch);
    // in range ? t : max range
    _mm256_store_pd(s.range + base, _mm256_blendv_pd(t, max_range_, Widen(beyond)));
    RC_STORE_I(sample, _mm_add_epi32(k, _mm_set1_epi32(1)));
    RC_STORE_I(nodes, nodes);
    const unsigned fetched = Bits(fetch), free = Bits(open);
    return {~(fetched & free) & 0xFu, fetched & ~free, fetched, index};
  }

  // One pass of CastRayMarching's loop for the lanes of group g: both ways
  // forward (the jump and the single exact step) computed, one selected.
  RC_LANES_TARGET StepResult StepRayMarching(LaneState& s, int g) const {
    const int base = g * kWidth;
    const __m256d ox = _mm256_load_pd(s.origin_x + base), oy = _mm256_load_pd(s.origin_y + base);
    const __m256d inv_x = _mm256_load_pd(s.inv_x + base), inv_y = _mm256_load_pd(s.inv_y + base);
    const __m256d exit_lim_x = _mm256_load_pd(s.exit_limit_x + base);
    const __m256d exit_lim_y = _mm256_load_pd(s.exit_limit_y + base);
    const __m128i exit_off_x = RC_LOAD_I(exit_offset_x), exit_off_y = RC_LOAD_I(exit_offset_y);
    __m256d t = _mm256_load_pd(s.t_enter + base);
    __m128i ix = RC_LOAD_I(ix), iy = RC_LOAD_I(iy), nodes = RC_LOAD_I(nodes);
    const Head h = LoopHead(t, ix, iy);
    const __m256d d =
        _mm256_cvtps_pd(_mm_mask_i32gather_ps(_mm_setzero_ps(), field_, h.index, _mm_castsi128_ps(h.fetch), 4));
    nodes = _mm_sub_epi32(nodes, h.fetch);
    const unsigned stops = static_cast<unsigned>(_mm256_movemask_pd(_mm256_cmp_pd(d, _mm256_setzero_pd(), _CMP_EQ_OQ)));
    const __m256d tx = _mm256_max_pd(exit_lim_x, BoundaryTime(ix, exit_off_x, r_, ox, inv_x));
    const __m256d ty = _mm256_max_pd(exit_lim_y, BoundaryTime(iy, exit_off_y, r_, oy, inv_y));
    const __m256d t_exit = _mm256_min_pd(ty, tx);  // std::min(tx, ty)
    // The jump from the cell's entry point, and the landing cell's entry and
    // exit times.
    const __m256d jump = _mm256_sub_pd(d, jump_margin_);
    const __m256d t_land = _mm256_add_pd(t, jump);
    const __m128i jx =
        FloorToCell(_mm256_div_pd(_mm256_add_pd(ox, _mm256_mul_pd(t_land, _mm256_load_pd(s.dir_x + base))), r_));
    const __m128i jy =
        FloorToCell(_mm256_div_pd(_mm256_add_pd(oy, _mm256_mul_pd(t_land, _mm256_load_pd(s.dir_y + base))), r_));
    const __m256d ex = _mm256_min_pd(_mm256_load_pd(s.entry_limit_x + base),
                                     BoundaryTime(jx, RC_LOAD_I(entry_offset_x), r_, ox, inv_x));
    const __m256d ey = _mm256_min_pd(_mm256_load_pd(s.entry_limit_y + base),
                                     BoundaryTime(jy, RC_LOAD_I(entry_offset_y), r_, oy, inv_y));
    const __m256d t_in = _mm256_max_pd(ey, ex);  // std::max(ex, ey)
    const __m256d bx = _mm256_max_pd(exit_lim_x, BoundaryTime(jx, exit_off_x, r_, ox, inv_x));
    const __m256d by = _mm256_max_pd(exit_lim_y, BoundaryTime(jy, exit_off_y, r_, oy, inv_y));
    const __m256d t_out = _mm256_min_pd(by, bx);  // std::min(bx, by)
    const __m256d jumps =
        _mm256_and_pd(_mm256_and_pd(_mm256_cmp_pd(jump, r_, _CMP_GT_OQ), _mm256_cmp_pd(t_in, t_out, _CMP_LT_OQ)),
                      _mm256_cmp_pd(t_in, t, _CMP_GT_OQ));
    const __m128i jumps_i = Narrow(jumps);
    // Otherwise CastDda's single step (x first on a tie).
    const __m128i step_x_first = Narrow(_mm256_cmp_pd(tx, ty, _CMP_LE_OQ));
    ix = _mm_add_epi32(ix, _mm_and_si128(step_x_first, RC_LOAD_I(step_x)));
    iy = _mm_add_epi32(iy, _mm_andnot_si128(step_x_first, RC_LOAD_I(step_y)));
    ix = _mm_blendv_epi8(ix, jx, jumps_i);
    iy = _mm_blendv_epi8(iy, jy, jumps_i);
    t = _mm256_blendv_pd(t_exit, t_in, jumps);
    _mm256_store_pd(s.t_enter + base, t);
    _mm256_store_pd(s.range + base, h.range);
    RC_STORE_I(ix, ix);
    RC_STORE_I(iy, iy);
    RC_STORE_I(nodes, nodes);
    const unsigned fetch = Bits(h.fetch);
    return {(~fetch | stops) & 0xFu, fetch & stops, fetch, h.index};
  }

  const void* cells_;
  const float* field_;
  __m256d r_, max_range_, jump_margin_;
  __m128i sign_, size_x_biased_, size_y_, size_y_biased_, byte_mask_, march_samples_;
  __m128i lane_bits_;  // bit i in lane i
  SectorOfCell sector_of_;
};

#undef RC_LOAD_I
#undef RC_STORE_I

#include "robocore/ray_lane_loop.inc"

}  // namespace

RC_LANES_TARGET void CastLanesAvx2(RayCastMethod method, const LaneScene& scene, const RayQuery* queries,
                                   std::size_t count, RayHit* hits, const LaneRecording* recording) {
  const Avx2Kernel kernel(scene, recording);
  RunLanes(method, kernel, scene, queries, count, hits, recording);
}

}  // namespace rc::ray_lanes

#else  // not x86-64: never called (RayLanesApply is false).

#include <stdexcept>

namespace rc::ray_lanes {

void CastLanesAvx2(RayCastMethod, const LaneScene&, const RayQuery*, std::size_t, RayHit*, const LaneRecording*) {
  throw std::logic_error("CastLanesAvx2: AVX2 exists only on x86-64");
}

}  // namespace rc::ray_lanes

#endif
