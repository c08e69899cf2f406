// The lane kernels in AVX2, for CPUs without AVX-512: the vector operations
// the steps (ray_lane_steps.inc) are written in, and the recording, with a
// store per lane. The contract (bit-identical hits) is in
// ray_batch_lanes.h; the shared state and loop in ray_lane_state.h and
// ray_lane_loop.inc.
#include "robocore/ray_lane_state.h"

#if defined(__x86_64__)
#include <immintrin.h>

#include <vector>

namespace rc::ray_lanes {
namespace {

#define RC_LANES_TARGET __attribute__((target("avx2")))

// The vector operations ray_lane_steps.inc names, in AVX2: eight groups of
// four rays, one __m256d of doubles per group. A mask is a vector of
// all-ones lanes, held both as 64-bit lanes (for doubles) and as 32-bit
// lanes (for cells and indices): each operation makes the form it has and
// converts to the other; the compiler drops a form nothing reads. Blends
// select exactly as AVX-512's masked moves do.
struct Avx2Vec {
  static constexpr int kWidth = 4;
  using D = __m256d;
  using I = __m128i;
  struct M {
    __m256d wide;
    __m128i narrow;
  };

  // A 32-bit lane mask widened to 64-bit lanes (sign extension keeps
  // all-ones all-ones), and a 64-bit mask narrowed (the low half of each).
  RC_LANES_TARGET static M FromNarrow(__m128i narrow) {
    return {_mm256_castsi256_pd(_mm256_cvtepi32_epi64(narrow)), narrow};
  }
  RC_LANES_TARGET static M FromWide(__m256d wide) {
    const __m256i low_halves = _mm256_setr_epi32(0, 2, 4, 6, 1, 3, 5, 7);
    return {wide, _mm256_castsi256_si128(_mm256_permutevar8x32_epi32(_mm256_castpd_si256(wide), low_halves))};
  }

  RC_LANES_TARGET static D Broadcast(double x) { return _mm256_set1_pd(x); }
  RC_LANES_TARGET static I BroadcastI(std::int32_t x) { return _mm_set1_epi32(x); }
  RC_LANES_TARGET static D LoadD(const double* p) { return _mm256_load_pd(p); }
  RC_LANES_TARGET static void StoreD(double* p, D v) { _mm256_store_pd(p, v); }
  RC_LANES_TARGET static I LoadI(const void* p) { return _mm_load_si128(static_cast<const __m128i*>(p)); }
  RC_LANES_TARGET static void StoreI(void* p, I v) { _mm_store_si128(static_cast<__m128i*>(p), v); }
  RC_LANES_TARGET static D Add(D a, D b) { return _mm256_add_pd(a, b); }
  RC_LANES_TARGET static D Sub(D a, D b) { return _mm256_sub_pd(a, b); }
  RC_LANES_TARGET static D Mul(D a, D b) { return _mm256_mul_pd(a, b); }
  RC_LANES_TARGET static D Div(D a, D b) { return _mm256_div_pd(a, b); }
  RC_LANES_TARGET static I AddI(I a, I b) { return _mm_add_epi32(a, b); }
  RC_LANES_TARGET static D Min(D a, D b) { return _mm256_min_pd(a, b); }
  RC_LANES_TARGET static D Max(D a, D b) { return _mm256_max_pd(a, b); }
  RC_LANES_TARGET static M CmpLe(D a, D b) { return FromWide(_mm256_cmp_pd(a, b, _CMP_LE_OQ)); }
  RC_LANES_TARGET static M CmpLt(D a, D b) { return FromWide(_mm256_cmp_pd(a, b, _CMP_LT_OQ)); }
  RC_LANES_TARGET static M CmpGt(D a, D b) { return FromWide(_mm256_cmp_pd(a, b, _CMP_GT_OQ)); }
  RC_LANES_TARGET static M CmpEq(D a, D b) { return FromWide(_mm256_cmp_pd(a, b, _CMP_EQ_OQ)); }
  RC_LANES_TARGET static M GreaterI(I a, I b) { return FromNarrow(_mm_cmpgt_epi32(a, b)); }
  RC_LANES_TARGET static M EqZero(I a) { return FromNarrow(_mm_cmpeq_epi32(a, _mm_setzero_si128())); }
  RC_LANES_TARGET static M And(M a, M b) { return {_mm256_and_pd(a.wide, b.wide), _mm_and_si128(a.narrow, b.narrow)}; }
  RC_LANES_TARGET static M AndNot(M a, M b) {
    return {_mm256_andnot_pd(b.wide, a.wide), _mm_andnot_si128(b.narrow, a.narrow)};
  }
  RC_LANES_TARGET static unsigned Bits(M m) {
    return static_cast<unsigned>(_mm_movemask_ps(_mm_castsi128_ps(m.narrow)));
  }
  RC_LANES_TARGET static D Select(M m, D a, D b) { return _mm256_blendv_pd(b, a, m.wide); }
  RC_LANES_TARGET static I SelectI(M m, I a, I b) { return _mm_blendv_epi8(b, a, m.narrow); }
  // All-ones is -1: a - mask adds 1 where the mask is set.
  RC_LANES_TARGET static I IncrementWhere(I a, M m) { return _mm_sub_epi32(a, m.narrow); }
  RC_LANES_TARGET static I AddWhere(I a, M m, I b) { return _mm_add_epi32(a, _mm_and_si128(m.narrow, b)); }
  RC_LANES_TARGET static I AddUnless(I a, M m, I b) { return _mm_add_epi32(a, _mm_andnot_si128(m.narrow, b)); }
  RC_LANES_TARGET static D ToDouble(I a) { return _mm256_cvtepi32_pd(a); }
  // Out of int range gives INT_MIN, as the AVX-512 conversion does.
  RC_LANES_TARGET static I FloorToCell(D x) {
    return _mm256_cvttpd_epi32(_mm256_round_pd(x, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC));
  }

  RC_LANES_TARGET explicit Avx2Vec(const LaneScene& scene)
      : cells_(scene.cells),
        field_(scene.field),
        sign_(_mm_set1_epi32(static_cast<int>(0x80000000u))),
        size_x_biased_(_mm_xor_si128(_mm_set1_epi32(scene.size_x), sign_)),
        size_y_(_mm_set1_epi32(scene.size_y)),
        size_y_biased_(_mm_xor_si128(size_y_, sign_)) {}

  // Unsigned 32-bit compares as signed ones with the sign bit flipped: a
  // negative cell is outside too.
  RC_LANES_TARGET M Inside(I ix, I iy) const {
    return FromNarrow(_mm_and_si128(_mm_cmplt_epi32(_mm_xor_si128(ix, sign_), size_x_biased_),
                                    _mm_cmplt_epi32(_mm_xor_si128(iy, sign_), size_y_biased_)));
  }
  RC_LANES_TARGET I Index(I ix, I iy) const { return _mm_add_epi32(_mm_mullo_epi32(ix, size_y_), iy); }
  // A 32-bit gather of the byte at each index (the gather cells are padded
  // for it), masked, then the byte.
  RC_LANES_TARGET I GatherCells(M m, I index) const {
    const __m128i words =
        _mm_mask_i32gather_epi32(_mm_setzero_si128(), static_cast<const int*>(cells_), index, m.narrow, 1);
    return _mm_and_si128(words, _mm_set1_epi32(0xFF));
  }
  RC_LANES_TARGET D GatherField(M m, I index) const {
    return _mm256_cvtps_pd(_mm_mask_i32gather_ps(_mm_setzero_ps(), field_, index, _mm_castsi128_ps(m.narrow), 4));
  }

 private:
  const void* cells_;
  const float* field_;
  __m128i sign_, size_x_biased_, size_y_, size_y_biased_;
};

#include "robocore/ray_lane_steps.inc"

// The steps, and the recording. AVX2 has no scatter: a recording marks
// sectors with a store per lane.
class Avx2Kernel : public LaneSteps<Avx2Vec> {
 public:
  RC_LANES_TARGET Avx2Kernel(const LaneScene& scene, const LaneRecording* rec)
      : LaneSteps<Avx2Vec>(scene), lane_bits_(_mm_setr_epi32(1, 2, 4, 8)) {
    // Fetches are masked to cells inside the map.
    if (rec) sector_of_ = SectorOfCell(*rec, scene.cell_count);
  }

  // Marks the sectors of a group's fetched cells (a recorded batch's touched
  // sectors) and logs their nodes. Where a sector is first + (index >>
  // shift) (SectorOfCell), every lane stores, with no branch per lane (the
  // fetch pattern is not predictable): a lane that did not fetch (rare: its
  // ray ends this step without a fetch, or the lanes are draining) stores
  // the first fetching lane's mark again. Elsewhere one lane at a time.
  RC_LANES_TARGET void Record(LaneState& s, const LaneStep<Avx2Vec>& step, unsigned fetch, int first,
                              const LaneRecording& rec) const {
    if (fetch == 0) return;
    alignas(16) std::int32_t index[kWidth];
    if (rec.nodes || !sector_of_.narrow) _mm_store_si128(reinterpret_cast<__m128i*>(index), step.index);
    if (rec.touched) {
      if (sector_of_.narrow) {
        __m128i sector = _mm_add_epi32(_mm_set1_epi32(sector_of_.first),
                                       _mm_srl_epi32(step.index, _mm_cvtsi32_si128(sector_of_.index_shift)));
        if (fetch != kAllLanes) {
          const __m128i lead =
              _mm_castps_si128(_mm_permutevar_ps(_mm_castsi128_ps(sector), _mm_set1_epi32(__builtin_ctz(fetch))));
          const __m128i fetched =
              _mm_cmpeq_epi32(_mm_and_si128(_mm_set1_epi32(static_cast<int>(fetch)), lane_bits_), lane_bits_);
          sector = _mm_blendv_epi8(lead, sector, fetched);
        }
        // Two 64-bit moves out of the vector, not four 32-bit extracts:
        // sectors are non-negative 32-bit values (SectorOfCell).
        const std::uint64_t low = static_cast<std::uint64_t>(_mm_cvtsi128_si64(sector));
        const std::uint64_t high = static_cast<std::uint64_t>(_mm_extract_epi64(sector, 1));
        std::uint8_t* const touched = rec.touched;
        touched[static_cast<std::uint32_t>(low)] = 1;
        touched[low >> 32] = 1;
        touched[static_cast<std::uint32_t>(high)] = 1;
        touched[high >> 32] = 1;
      } else {
        for (unsigned m = fetch; m != 0; m &= m - 1) {
          const std::uint32_t cell = static_cast<std::uint32_t>(index[__builtin_ctz(m)]);
          rec.touched[(rec.offset + std::uint64_t{cell} * rec.element_bytes) >> rec.sector_shift] = 1;
        }
      }
    }
    if (rec.nodes) LogNodes<kWidth>(s, index, fetch, first, *rec.nodes);
  }
  // Record marks as it goes: nothing is pending.
  void FinishRecording() {}

 private:
  static constexpr unsigned kAllLanes = (1u << kWidth) - 1;
  __m128i lane_bits_;  // bit i in lane i
  SectorOfCell sector_of_;
};

#include "robocore/ray_lane_loop.inc"

}  // namespace

RC_LANES_TARGET void CastLanesAvx2(RayCastMethod method, const LaneScene& scene, const RayQuery* queries,
                                   std::size_t count, RayHit* hits, const LaneRecording* recording) {
  Avx2Kernel kernel(scene, recording);
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
