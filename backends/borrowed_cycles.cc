#include "backends/borrowed_cycles.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/avx512_warnings.h"

#if defined(__x86_64__)
RC_AVX512_WARNINGS_OFF
#include <immintrin.h>
#endif

#include "common/cpu_features.h"

namespace rc {

void WriteBorrowedCyclesScalar(const std::uint32_t* rank, const std::uint32_t* nodes, std::size_t count,
                               const double* rate, std::size_t rate_count, double fallback, std::uint64_t l1_latency,
                               std::uint64_t* cycles) {
  for (std::size_t i = 0; i < count; ++i) {
    cycles[i] = l1_latency * nodes[i];
    AddRoundedCycles(cycles[i], (rank[i] < rate_count ? rate[rank[i]] : fallback) * nodes[i]);
  }
}

#if defined(__x86_64__)

// Eight lanes a step: the rates gathered by rank, the products and their
// rounding in vectors; a step with a product outside [0, 2^63) goes lane by
// lane instead.
__attribute__((target("avx512f,avx512dq,avx512vl"))) void WriteBorrowedCyclesLanes(
    const std::uint32_t* rank, const std::uint32_t* nodes, std::size_t count, const double* rate,
    std::size_t rate_count, double fallback, std::uint64_t l1_latency, std::uint64_t* cycles) {
  // Ranks are 32-bit: with more rates than that, every rank has one.
  const bool every_rank = rate_count > 0xFFFFFFFFu;
  const __m256i limit = _mm256_set1_epi32(static_cast<int>(static_cast<std::uint32_t>(every_rank ? 0 : rate_count)));
  const __m512d otherwise = _mm512_set1_pd(fallback);
  const __m512d zero = _mm512_setzero_pd(), top = _mm512_set1_pd(0x1p63), half = _mm512_set1_pd(0.5);
  const __m512i l1 = _mm512_set1_epi64(static_cast<long long>(l1_latency));
  for (std::size_t i = 0; i < count; i += 8) {
    const auto in = static_cast<__mmask8>(count - i >= 8 ? 0xFF : (1u << (count - i)) - 1);
    const __m256i r = _mm256_maskz_loadu_epi32(in, rank + i);
    const __m256i k = _mm256_maskz_loadu_epi32(in, nodes + i);
    const __mmask8 ranked = every_rank ? in : _mm256_mask_cmplt_epu32_mask(in, r, limit);
    const __m512d borrowed = _mm512_mask_i32gather_pd(otherwise, ranked, r, rate, 8);
    const __m512d extra = _mm512_mul_pd(borrowed, _mm512_cvtepu32_pd(k));
    const __mmask8 inline_ok = _mm512_cmp_pd_mask(extra, zero, _CMP_GE_OQ) & _mm512_cmp_pd_mask(extra, top, _CMP_LT_OQ);
    if ((inline_ok & in) != in) {
      WriteBorrowedCyclesScalar(rank + i, nodes + i, count - i < 8 ? count - i : 8, rate, rate_count, fallback,
                                l1_latency, cycles + i);
      continue;
    }
    const __m512i whole = _mm512_cvttpd_epi64(extra);
    const __mmask8 up = _mm512_cmp_pd_mask(_mm512_sub_pd(extra, _mm512_cvtepi64_pd(whole)), half, _CMP_GE_OQ);
    __m512i c = _mm512_mullo_epi64(_mm512_cvtepu32_epi64(k), l1);
    c = _mm512_add_epi64(c, whole);
    c = _mm512_mask_add_epi64(c, up, c, _mm512_set1_epi64(1));
    _mm512_mask_storeu_epi64(cycles + i, in, c);
  }
}

RC_AVX512_WARNINGS_ON

#else  // not x86-64: never called (UseAvx512() is false).

void WriteBorrowedCyclesLanes(const std::uint32_t*, const std::uint32_t*, std::size_t, const double*, std::size_t,
                              double, std::uint64_t, std::uint64_t*) {
  throw std::logic_error("WriteBorrowedCyclesLanes: AVX-512 exists only on x86-64");
}

#endif

void WriteBorrowedCycles(const std::uint32_t* rank, const std::uint32_t* nodes, std::size_t count, const double* rate,
                         std::size_t rate_count, double fallback, std::uint64_t l1_latency, std::uint64_t* cycles) {
  if (UseAvx512())
    WriteBorrowedCyclesLanes(rank, nodes, count, rate, rate_count, fallback, l1_latency, cycles);
  else
    WriteBorrowedCyclesScalar(rank, nodes, count, rate, rate_count, fallback, l1_latency, cycles);
}

}  // namespace rc
