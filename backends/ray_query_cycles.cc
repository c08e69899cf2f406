#include "backends/ray_query_cycles.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "common/avx512_warnings.h"

#if defined(__x86_64__)
RC_AVX512_WARNINGS_OFF
#include <immintrin.h>
#endif

#include "common/cpu_features.h"

namespace rc {

std::uint64_t SlowestRayQueryScalar(const RayQueryTerms& t, std::size_t lo, std::size_t hi, RayPassTally& tally) {
  std::uint64_t slowest = 0;
  for (std::size_t q = lo; q < hi; ++q) {
    std::uint64_t cycles = t.once_cycles + t.memory_cycles[q];
    const std::uint64_t nodes = t.fetch_offsets[q + 1] - t.fetch_offsets[q];
    if (nodes > 0) {
      const std::uint8_t last = t.last_exits[q];
      cycles += (nodes - 1) * t.quiet_pass_cycles + t.last_pass_cycles[last];
      tally.quiet += nodes - 1;
      if (last < t.exits)
        ++tally.exit[last];
      else
        ++tally.quiet;
    }
    slowest = std::max(slowest, cycles);
  }
  return slowest;
}

#if defined(__x86_64__)

// Eight queries a step, the last step masked. Passes are counted per step
// from masks: the quiet ones as a vector sum, each exit's by population
// count, so that no count waits on the previous query's.
__attribute__((target("avx512f,avx512dq"))) std::uint64_t SlowestRayQueryLanes(const RayQueryTerms& t, std::size_t lo,
                                                                               std::size_t hi, RayPassTally& tally) {
  const __m512i once = _mm512_set1_epi64(static_cast<long long>(t.once_cycles));
  const __m512i quiet_cycles = _mm512_set1_epi64(static_cast<long long>(t.quiet_pass_cycles));
  const __m512i one = _mm512_set1_epi64(1);
  __m512i slowest = _mm512_setzero_si512();
  __m512i quiet = _mm512_setzero_si512();
  std::uint64_t with_nodes = 0, exiting = 0;
  // With at most 7 exits (a ray program has two), the last pass's cycles
  // come from a register rather than a gather: exit e at min(e, 7), whose
  // entry 7 is the table's last (every entry from `exits` on is a quiet
  // pass, RayQueryTerms' contract).
  const bool in_register = t.exits < 8;
  const bool narrow_quiet = t.quiet_pass_cycles <= 0xFFFFFFFFu;
  const __m512i seven = _mm512_set1_epi64(7);
  const __m512i last_pass = _mm512_loadu_si512(t.last_pass_cycles.data());
  const __m512i by_exit = _mm512_mask_set1_epi64(last_pass, 0x80, static_cast<long long>(t.last_pass_cycles.back()));
  for (std::size_t q = lo; q < hi; q += 8) {
    const auto in = static_cast<__mmask8>(hi - q >= 8 ? 0xFF : (1u << (hi - q)) - 1);
    const __m512i begin = _mm512_maskz_loadu_epi64(in, t.fetch_offsets + q);
    const __m512i end = _mm512_maskz_loadu_epi64(in, t.fetch_offsets + q + 1);
    const __m512i nodes = _mm512_sub_epi64(end, begin);
    const __mmask8 has = _mm512_mask_cmpneq_epu64_mask(in, nodes, _mm512_setzero_si512());
    std::uint64_t packed = 0;
    if (in == 0xFF)
      std::memcpy(&packed, t.last_exits + q, 8);
    else
      for (std::size_t i = 0; q + i < hi; ++i) packed |= std::uint64_t{t.last_exits[q + i]} << (8 * i);
    const __m512i exit = _mm512_cvtepu8_epi64(_mm_cvtsi64_si128(static_cast<long long>(packed)));
    const __m512i last =
        in_register ? _mm512_maskz_permutexvar_epi64(has, _mm512_min_epu64(exit, seven), by_exit)
                    : _mm512_mask_i64gather_epi64(_mm512_setzero_si512(), has, exit,
                                                  reinterpret_cast<const long long*>(t.last_pass_cycles.data()), 8);
    const __m512i before_last = _mm512_sub_epi64(nodes, one);
    // A 32 x 32-bit product where it is exact (a query's nodes fit 32 bits,
    // RayHit::nodes): one instruction against vpmullq's three. Lanes without
    // nodes are masked out below.
    const __m512i product =
        narrow_quiet ? _mm512_mul_epu32(before_last, quiet_cycles) : _mm512_mullo_epi64(before_last, quiet_cycles);
    const __m512i passes = _mm512_add_epi64(product, last);
    __m512i cycles = _mm512_add_epi64(once, _mm512_maskz_loadu_epi64(in, t.memory_cycles + q));
    cycles = _mm512_mask_add_epi64(cycles, has, cycles, passes);
    slowest = _mm512_mask_max_epu64(slowest, in, slowest, cycles);
    quiet = _mm512_mask_add_epi64(quiet, has, quiet, before_last);
    with_nodes += static_cast<std::uint64_t>(__builtin_popcount(has));
    for (int j = 0; j < t.exits; ++j) {
      const auto n =
          static_cast<std::uint64_t>(__builtin_popcount(_mm512_mask_cmpeq_epi64_mask(has, exit, _mm512_set1_epi64(j))));
      tally.exit[j] += n;
      exiting += n;
    }
  }
  tally.quiet += with_nodes - exiting + static_cast<std::uint64_t>(_mm512_reduce_add_epi64(quiet));
  return static_cast<std::uint64_t>(_mm512_reduce_max_epu64(slowest));
}

// Four queries a step in AVX2, as the AVX-512 form but without mask
// registers (masks are all-ones lanes), a 64-bit multiply (the quiet passes
// are a 32 x 32-bit product: a query's nodes fit 32 bits, RayHit::nodes,
// and a quiet pass's cycles are checked to) or an unsigned 64-bit maximum
// (a signed one on values with the sign bit flipped).
__attribute__((target("avx2"))) std::uint64_t SlowestRayQueryAvx2(const RayQueryTerms& t, std::size_t lo,
                                                                  std::size_t hi, RayPassTally& tally) {
  if (t.quiet_pass_cycles > 0xFFFFFFFFu) return SlowestRayQueryScalar(t, lo, hi, tally);
  const __m256i once = _mm256_set1_epi64x(static_cast<long long>(t.once_cycles));
  const __m256i quiet_cycles = _mm256_set1_epi64x(static_cast<long long>(t.quiet_pass_cycles));
  const __m256i one = _mm256_set1_epi64x(1);
  const __m256i sign = _mm256_set1_epi64x(static_cast<long long>(0x8000000000000000u));
  const __m256i lane = _mm256_setr_epi64x(0, 1, 2, 3);
  const auto* last_pass = reinterpret_cast<const long long*>(t.last_pass_cycles.data());
  __m256i slowest = sign;  // 0, sign flipped
  __m256i quiet = _mm256_setzero_si256();
  std::uint64_t with_nodes = 0, exiting = 0;
  for (std::size_t q = lo; q < hi; q += 4) {
    const std::size_t left = hi - q;
    const __m256i in = _mm256_cmpgt_epi64(_mm256_set1_epi64x(static_cast<long long>(left < 4 ? left : 4)), lane);
    const auto* offsets = reinterpret_cast<const long long*>(t.fetch_offsets + q);
    const __m256i nodes = _mm256_sub_epi64(_mm256_maskload_epi64(offsets + 1, in), _mm256_maskload_epi64(offsets, in));
    const __m256i has = _mm256_andnot_si256(_mm256_cmpeq_epi64(nodes, _mm256_setzero_si256()), in);
    std::uint32_t packed = 0;
    if (left >= 4)
      std::memcpy(&packed, t.last_exits + q, 4);
    else
      for (std::size_t i = 0; i < left; ++i) packed |= std::uint32_t{t.last_exits[q + i]} << (8 * i);
    const __m256i exit = _mm256_cvtepu8_epi64(_mm_cvtsi32_si128(static_cast<int>(packed)));
    const __m256i last = _mm256_mask_i64gather_epi64(_mm256_setzero_si256(), last_pass, exit, has, 8);
    const __m256i before_last = _mm256_and_si256(_mm256_sub_epi64(nodes, one), has);
    const __m256i passes = _mm256_add_epi64(_mm256_mul_epu32(before_last, quiet_cycles), last);
    __m256i cycles =
        _mm256_add_epi64(once, _mm256_maskload_epi64(reinterpret_cast<const long long*>(t.memory_cycles + q), in));
    cycles = _mm256_add_epi64(cycles, _mm256_and_si256(passes, has));
    const __m256i flipped = _mm256_xor_si256(cycles, sign);
    const __m256i larger = _mm256_and_si256(_mm256_cmpgt_epi64(flipped, slowest), in);
    slowest = _mm256_blendv_epi8(slowest, flipped, larger);
    quiet = _mm256_add_epi64(quiet, before_last);
    const __m256d has_pd = _mm256_castsi256_pd(has);
    with_nodes += static_cast<std::uint64_t>(__builtin_popcount(_mm256_movemask_pd(has_pd)));
    for (int j = 0; j < t.exits; ++j) {
      const __m256i is_j = _mm256_and_si256(_mm256_cmpeq_epi64(exit, _mm256_set1_epi64x(j)), has);
      const auto n = static_cast<std::uint64_t>(__builtin_popcount(_mm256_movemask_pd(_mm256_castsi256_pd(is_j))));
      tally.exit[j] += n;
      exiting += n;
    }
  }
  alignas(32) std::uint64_t lanes[4], quiets[4];
  _mm256_store_si256(reinterpret_cast<__m256i*>(lanes), _mm256_xor_si256(slowest, sign));
  _mm256_store_si256(reinterpret_cast<__m256i*>(quiets), quiet);
  tally.quiet += with_nodes - exiting + quiets[0] + quiets[1] + quiets[2] + quiets[3];
  return std::max(std::max(lanes[0], lanes[1]), std::max(lanes[2], lanes[3]));
}

RC_AVX512_WARNINGS_ON

#else

std::uint64_t SlowestRayQueryLanes(const RayQueryTerms&, std::size_t, std::size_t, RayPassTally&) {
  throw std::logic_error("SlowestRayQueryLanes: AVX-512 exists only on x86-64");
}

std::uint64_t SlowestRayQueryAvx2(const RayQueryTerms&, std::size_t, std::size_t, RayPassTally&) {
  throw std::logic_error("SlowestRayQueryAvx2: AVX2 exists only on x86-64");
}

#endif

std::uint64_t SlowestRayQuery(const RayQueryTerms& terms, std::size_t lo, std::size_t hi, RayPassTally& tally) {
  if (UseAvx512()) return SlowestRayQueryLanes(terms, lo, hi, tally);
  if (UseAvx2()) return SlowestRayQueryAvx2(terms, lo, hi, tally);
  return SlowestRayQueryScalar(terms, lo, hi, tally);
}

}  // namespace rc
