// The lane kernels in AVX-512 (F, VL, DQ): the vector operations the steps
// (ray_lane_steps.inc) are written in, and the recording, with a scatter.
// The contract (bit-identical hits) and the reasons are in
// ray_batch_lanes.h; the shared state and loop in ray_lane_state.h and
// ray_lane_loop.inc.
#include "robocore/ray_lane_state.h"

#include "common/avx512_warnings.h"

#if defined(__x86_64__)
RC_AVX512_WARNINGS_OFF
#include <immintrin.h>

#include <vector>

namespace rc::ray_lanes {
namespace {

#define RC_LANES_TARGET __attribute__((target("avx512f,avx512vl,avx512dq")))

// The vector operations ray_lane_steps.inc names, in AVX-512: four groups
// of eight rays, one __m512d of doubles per group, every mask a __mmask8.
struct Avx512Vec {
  static constexpr int kWidth = 8;
  using D = __m512d;
  using I = __m256i;
  using M = __mmask8;

  RC_LANES_TARGET static D Broadcast(double x) { return _mm512_set1_pd(x); }
  RC_LANES_TARGET static I BroadcastI(std::int32_t x) { return _mm256_set1_epi32(x); }
  RC_LANES_TARGET static D LoadD(const double* p) { return _mm512_load_pd(p); }
  RC_LANES_TARGET static void StoreD(double* p, D v) { _mm512_store_pd(p, v); }
  RC_LANES_TARGET static I LoadI(const void* p) { return _mm256_load_si256(static_cast<const __m256i*>(p)); }
  RC_LANES_TARGET static void StoreI(void* p, I v) { _mm256_store_si256(static_cast<__m256i*>(p), v); }
  RC_LANES_TARGET static D Add(D a, D b) { return _mm512_add_pd(a, b); }
  RC_LANES_TARGET static D Sub(D a, D b) { return _mm512_sub_pd(a, b); }
  RC_LANES_TARGET static D Mul(D a, D b) { return _mm512_mul_pd(a, b); }
  RC_LANES_TARGET static D Div(D a, D b) { return _mm512_div_pd(a, b); }
  RC_LANES_TARGET static I AddI(I a, I b) { return _mm256_add_epi32(a, b); }
  RC_LANES_TARGET static D Min(D a, D b) { return _mm512_min_pd(a, b); }
  RC_LANES_TARGET static D Max(D a, D b) { return _mm512_max_pd(a, b); }
  RC_LANES_TARGET static M CmpLe(D a, D b) { return _mm512_cmp_pd_mask(a, b, _CMP_LE_OQ); }
  RC_LANES_TARGET static M CmpLt(D a, D b) { return _mm512_cmp_pd_mask(a, b, _CMP_LT_OQ); }
  RC_LANES_TARGET static M CmpGt(D a, D b) { return _mm512_cmp_pd_mask(a, b, _CMP_GT_OQ); }
  RC_LANES_TARGET static M CmpEq(D a, D b) { return _mm512_cmp_pd_mask(a, b, _CMP_EQ_OQ); }
  RC_LANES_TARGET static M GreaterI(I a, I b) { return _mm256_cmpgt_epi32_mask(a, b); }
  RC_LANES_TARGET static M EqZero(I a) { return _mm256_cmpeq_epi32_mask(a, _mm256_setzero_si256()); }
  RC_LANES_TARGET static M And(M a, M b) { return static_cast<M>(a & b); }
  RC_LANES_TARGET static M AndNot(M a, M b) { return static_cast<M>(a & ~b); }
  RC_LANES_TARGET static unsigned Bits(M m) { return m; }
  RC_LANES_TARGET static D Select(M m, D a, D b) { return _mm512_mask_mov_pd(b, m, a); }
  RC_LANES_TARGET static I SelectI(M m, I a, I b) { return _mm256_mask_mov_epi32(b, m, a); }
  RC_LANES_TARGET static I IncrementWhere(I a, M m) { return _mm256_mask_add_epi32(a, m, a, _mm256_set1_epi32(1)); }
  RC_LANES_TARGET static I AddWhere(I a, M m, I b) { return _mm256_mask_add_epi32(a, m, a, b); }
  RC_LANES_TARGET static I AddUnless(I a, M m, I b) { return _mm256_mask_add_epi32(a, static_cast<M>(~m), a, b); }
  RC_LANES_TARGET static D ToDouble(I a) { return _mm512_cvtepi32_pd(a); }
  // CastMarch's and CastRayMarching's static_cast<int>(std::floor(...)).
  RC_LANES_TARGET static I FloorToCell(D x) {
    constexpr int kFloor = _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC;
    return _mm512_cvttpd_epi32(_mm512_roundscale_pd(x, kFloor));
  }

  RC_LANES_TARGET explicit Avx512Vec(const LaneScene& scene)
      : cells_(scene.cells),
        field_(scene.field),
        size_x_(_mm256_set1_epi32(scene.size_x)),
        size_y_(_mm256_set1_epi32(scene.size_y)) {}

  // Unsigned compares: a negative cell is outside too.
  RC_LANES_TARGET M Inside(I ix, I iy) const {
    return static_cast<M>(_mm256_cmplt_epu32_mask(ix, size_x_) & _mm256_cmplt_epu32_mask(iy, size_y_));
  }
  RC_LANES_TARGET I Index(I ix, I iy) const { return _mm256_add_epi32(_mm256_mullo_epi32(ix, size_y_), iy); }
  // A 32-bit gather of the byte at each index (the gather cells are padded
  // for it), masked, then the byte.
  RC_LANES_TARGET I GatherCells(M m, I index) const {
    return _mm256_and_si256(_mm256_mmask_i32gather_epi32(_mm256_setzero_si256(), m, index, cells_, 1),
                            _mm256_set1_epi32(0xFF));
  }
  RC_LANES_TARGET D GatherField(M m, I index) const {
    return _mm512_cvtps_pd(_mm256_mmask_i32gather_ps(_mm256_setzero_ps(), m, index, field_, 4));
  }

 private:
  const void* cells_;
  const float* field_;
  I size_x_, size_y_;
};

#include "robocore/ray_lane_steps.inc"

// The steps, and the recording: a batch's touched sectors queued with one
// store per group (SectorQueue) and marked in bulk, and the nodes logged.
class Avx512Kernel : public LaneSteps<Avx512Vec> {
 public:
  RC_LANES_TARGET Avx512Kernel(const LaneScene& scene, const LaneRecording* rec)
      : LaneSteps<Avx512Vec>(scene), sectors_(rec ? rec->touched : nullptr) {
    // Fetches are masked to cells inside the map.
    if (rec) sector_of_ = SectorOfCell(*rec, scene.cell_count);
  }

  RC_LANES_TARGET void Record(LaneState& s, const LaneStep<Avx512Vec>& step, unsigned fetch, int first,
                              const LaneRecording& rec) {
    if (fetch == 0) return;
    const __mmask8 m = static_cast<__mmask8>(fetch);
    if (rec.touched) {
      if (sector_of_.narrow) {
        // All eight lanes' sectors go to the queue, a lane that did not
        // fetch (rare: its ray ended without a fetch, or the lanes are
        // draining) with the first fetching lane's sector again. Packing only
        // the fetching lanes (a compress and a count) measured slower.
        const __m256i sector =
            _mm256_add_epi32(_mm256_set1_epi32(sector_of_.first),
                             _mm256_srl_epi32(step.index, _mm_cvtsi32_si128(sector_of_.index_shift)));
        const __m256i lead = _mm256_permutexvar_epi32(_mm256_set1_epi32(__builtin_ctz(fetch)), sector);
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(sectors_.end()), _mm256_mask_mov_epi32(lead, m, sector));
        static_assert(kWidth <= SectorQueue::kMaxAppend);
        sectors_.Append(kWidth);
      } else {
        const __m512i index = _mm512_cvtepu32_epi64(step.index);
        const __m512i byte = _mm512_add_epi64(_mm512_set1_epi64(static_cast<long long>(rec.offset)),
                                              _mm512_mullo_epi64(index, _mm512_set1_epi64(rec.element_bytes)));
        alignas(64) std::uint64_t sector[kWidth];
        _mm512_store_si512(sector, _mm512_srl_epi64(byte, _mm_cvtsi32_si128(rec.sector_shift)));
        for (unsigned f = fetch; f != 0; f &= f - 1) rec.touched[sector[__builtin_ctz(f)]] = 1;
      }
    }
    if (rec.nodes) {
      // LogNodes in vectors: the fetching lanes' cells scattered to their
      // lanes' write positions (absolute addresses, 64-bit), which then move.
      auto* at_of = reinterpret_cast<long long*>(s.log_at + first);
      __m512i at = _mm512_loadu_si512(at_of);
      _mm512_mask_i64scatter_epi32(nullptr, m, at, step.index, 1);
      at = _mm512_mask_add_epi64(at, m, at, _mm512_set1_epi64(sizeof(std::uint32_t)));
      _mm512_storeu_si512(at_of, at);
      const __mmask8 full = _mm512_cmpeq_epu64_mask(at, _mm512_loadu_si512(s.log_end + first));
      for (unsigned f = full; __builtin_expect(f != 0, 0); f &= f - 1) {
        const int l = first + __builtin_ctz(f);
        s.log_at[l] = GrowNodeLog(s, l, *rec.nodes);
      }
    }
  }
  void FinishRecording() { sectors_.Mark(); }

 private:
  SectorOfCell sector_of_;
  SectorQueue sectors_;  // of the narrow sectors (SectorOfCell); wide ones are marked at once
};

#include "robocore/ray_lane_loop.inc"

}  // namespace

RC_LANES_TARGET void CastLanesAvx512(RayCastMethod method, const LaneScene& scene, const RayQuery* queries,
                                     std::size_t count, RayHit* hits, const LaneRecording* recording) {
  Avx512Kernel kernel(scene, recording);
  RunLanes(method, kernel, scene, queries, count, hits, recording);
}

}  // namespace rc::ray_lanes

RC_AVX512_WARNINGS_ON

#else  // not x86-64: never called (RayLanesApply is false).

#include <stdexcept>

namespace rc::ray_lanes {

void CastLanesAvx512(RayCastMethod, const LaneScene&, const RayQuery*, std::size_t, RayHit*, const LaneRecording*) {
  throw std::logic_error("CastLanesAvx512: AVX-512 exists only on x86-64");
}

}  // namespace rc::ray_lanes

#endif
