#include "backends/ray_query_cycles.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

#include "common/avx512_warnings.h"

#if defined(__x86_64__)
RC_AVX512_WARNINGS_OFF
#include <immintrin.h>
#endif

#include "common/cpu_features.h"

namespace rc {
namespace {

void CheckCount(int count) {
  if (count < 1 || count > kMaxRayCostsPerPass)
    throw std::invalid_argument("SlowestRayQueries: 1 to " + std::to_string(kMaxRayCostsPerPass) + " costs, got " +
                                std::to_string(count));
}

}  // namespace

void SlowestRayQueriesScalar(const RayQueryArrays& a, const RayPassCosts* costs, int count, std::size_t lo,
                             std::size_t hi, std::uint64_t* slowest, RayPassTally& tally) {
  CheckCount(count);
  std::fill(slowest, slowest + count, 0);
  for (std::size_t q = lo; q < hi; ++q) {
    const std::uint64_t nodes = a.fetch_offsets[q + 1] - a.fetch_offsets[q];
    const std::uint8_t last = a.last_exits[q];
    if (nodes > 0) {
      tally.quiet += nodes - 1;
      if (last < a.exits)
        ++tally.exit[last];
      else
        ++tally.quiet;
    }
    for (int k = 0; k < count; ++k) {
      const RayPassCosts& c = costs[k];
      std::uint64_t cycles = c.once_cycles + a.memory_cycles[q];
      if (nodes > 0) cycles += (nodes - 1) * c.quiet_pass_cycles + c.last_pass_cycles[last];
      slowest[k] = std::max(slowest[k], cycles);
    }
  }
}

#if defined(__x86_64__)

// Eight queries a step, the last step masked; per step the arrays are read
// once and each unit's cycles follow in registers. The once-per-query
// cycles are the same for every query, so they join the maximum at the
// end. Passes are counted per step from masks: the quiet ones as a vector
// sum, each exit's by population count, so that no count waits on the
// previous query's.
__attribute__((target("avx512f,avx512dq"))) void SlowestRayQueriesLanes(const RayQueryArrays& a,
                                                                        const RayPassCosts* costs, int count,
                                                                        std::size_t lo, std::size_t hi,
                                                                        std::uint64_t* slowest, RayPassTally& tally) {
  CheckCount(count);
  if (lo >= hi) {
    std::fill(slowest, slowest + count, 0);
    return;
  }
  const __m512i one = _mm512_set1_epi64(1);
  // With at most 7 exits (a ray program has two), the last pass's cycles
  // come from a register rather than a gather: exit e at min(e, 7), whose
  // entry 7 is the table's last (every entry from `exits` on is a quiet
  // pass, RayPassCosts' contract).
  const bool in_register = a.exits < 8;
  const __m512i seven = _mm512_set1_epi64(7);
  bool narrow_quiet = true;
  __m512i quiet_cycles[kMaxRayCostsPerPass], by_exit[kMaxRayCostsPerPass], most[kMaxRayCostsPerPass];
  for (int k = 0; k < count; ++k) {
    const RayPassCosts& c = costs[k];
    narrow_quiet = narrow_quiet && c.quiet_pass_cycles <= 0xFFFFFFFFu;
    quiet_cycles[k] = _mm512_set1_epi64(static_cast<long long>(c.quiet_pass_cycles));
    by_exit[k] = _mm512_mask_set1_epi64(_mm512_loadu_si512(c.last_pass_cycles.data()), 0x80,
                                        static_cast<long long>(c.last_pass_cycles.back()));
    most[k] = _mm512_setzero_si512();
  }
  __m512i quiet = _mm512_setzero_si512();
  std::uint64_t with_nodes = 0, exiting = 0;
  for (std::size_t q = lo; q < hi; q += 8) {
    const auto in = static_cast<__mmask8>(hi - q >= 8 ? 0xFF : (1u << (hi - q)) - 1);
    const __m512i begin = _mm512_maskz_loadu_epi64(in, a.fetch_offsets + q);
    const __m512i end = _mm512_maskz_loadu_epi64(in, a.fetch_offsets + q + 1);
    const __m512i nodes = _mm512_sub_epi64(end, begin);
    const __mmask8 has = _mm512_mask_cmpneq_epu64_mask(in, nodes, _mm512_setzero_si512());
    std::uint64_t packed = 0;
    if (in == 0xFF)
      std::memcpy(&packed, a.last_exits + q, 8);
    else
      for (std::size_t i = 0; q + i < hi; ++i) packed |= std::uint64_t{a.last_exits[q + i]} << (8 * i);
    const __m512i exit = _mm512_cvtepu8_epi64(_mm_cvtsi64_si128(static_cast<long long>(packed)));
    const __m512i exit_slot = _mm512_min_epu64(exit, seven);
    const __m512i before_last = _mm512_sub_epi64(nodes, one);
    const __m512i memory = _mm512_maskz_loadu_epi64(in, a.memory_cycles + q);
    for (int k = 0; k < count; ++k) {
      const __m512i last =
          in_register
              ? _mm512_maskz_permutexvar_epi64(has, exit_slot, by_exit[k])
              : _mm512_mask_i64gather_epi64(_mm512_setzero_si512(), has, exit,
                                            reinterpret_cast<const long long*>(costs[k].last_pass_cycles.data()), 8);
      // A 32 x 32-bit product where it is exact (a query's nodes fit 32
      // bits, RayHit::nodes): one instruction against vpmullq's three.
      // Lanes without nodes are masked out below.
      const __m512i product = narrow_quiet ? _mm512_mul_epu32(before_last, quiet_cycles[k])
                                           : _mm512_mullo_epi64(before_last, quiet_cycles[k]);
      const __m512i cycles = _mm512_mask_add_epi64(memory, has, memory, _mm512_add_epi64(product, last));
      most[k] = _mm512_mask_max_epu64(most[k], in, most[k], cycles);
    }
    quiet = _mm512_mask_add_epi64(quiet, has, quiet, before_last);
    with_nodes += static_cast<std::uint64_t>(__builtin_popcount(has));
    for (int j = 0; j < a.exits; ++j) {
      const auto n =
          static_cast<std::uint64_t>(__builtin_popcount(_mm512_mask_cmpeq_epi64_mask(has, exit, _mm512_set1_epi64(j))));
      tally.exit[j] += n;
      exiting += n;
    }
  }
  tally.quiet += with_nodes - exiting + static_cast<std::uint64_t>(_mm512_reduce_add_epi64(quiet));
  for (int k = 0; k < count; ++k)
    slowest[k] = costs[k].once_cycles + static_cast<std::uint64_t>(_mm512_reduce_max_epu64(most[k]));
}

// Four queries a step in AVX2, as the AVX-512 form but without mask
// registers (masks are all-ones lanes), a 64-bit multiply (the quiet passes
// are a 32 x 32-bit product: a query's nodes fit 32 bits, RayHit::nodes,
// and a quiet pass's cycles are checked to) or an unsigned 64-bit maximum
// (a signed one on values with the sign bit flipped).
__attribute__((target("avx2"))) void SlowestRayQueriesAvx2(const RayQueryArrays& a, const RayPassCosts* costs,
                                                           int count, std::size_t lo, std::size_t hi,
                                                           std::uint64_t* slowest, RayPassTally& tally) {
  CheckCount(count);
  for (int k = 0; k < count; ++k)
    if (costs[k].quiet_pass_cycles > 0xFFFFFFFFu)
      return SlowestRayQueriesScalar(a, costs, count, lo, hi, slowest, tally);
  if (lo >= hi) {
    std::fill(slowest, slowest + count, 0);
    return;
  }
  const __m256i one = _mm256_set1_epi64x(1);
  const __m256i sign = _mm256_set1_epi64x(static_cast<long long>(0x8000000000000000u));
  const __m256i lane = _mm256_setr_epi64x(0, 1, 2, 3);
  __m256i quiet_cycles[kMaxRayCostsPerPass], most[kMaxRayCostsPerPass];
  for (int k = 0; k < count; ++k) {
    quiet_cycles[k] = _mm256_set1_epi64x(static_cast<long long>(costs[k].quiet_pass_cycles));
    most[k] = sign;  // 0, sign flipped
  }
  __m256i quiet = _mm256_setzero_si256();
  std::uint64_t with_nodes = 0, exiting = 0;
  for (std::size_t q = lo; q < hi; q += 4) {
    const std::size_t left = hi - q;
    const __m256i in = _mm256_cmpgt_epi64(_mm256_set1_epi64x(static_cast<long long>(left < 4 ? left : 4)), lane);
    const auto* offsets = reinterpret_cast<const long long*>(a.fetch_offsets + q);
    const __m256i nodes = _mm256_sub_epi64(_mm256_maskload_epi64(offsets + 1, in), _mm256_maskload_epi64(offsets, in));
    const __m256i has = _mm256_andnot_si256(_mm256_cmpeq_epi64(nodes, _mm256_setzero_si256()), in);
    std::uint32_t packed = 0;
    if (left >= 4)
      std::memcpy(&packed, a.last_exits + q, 4);
    else
      for (std::size_t i = 0; i < left; ++i) packed |= std::uint32_t{a.last_exits[q + i]} << (8 * i);
    const __m256i exit = _mm256_cvtepu8_epi64(_mm_cvtsi32_si128(static_cast<int>(packed)));
    const __m256i before_last = _mm256_and_si256(_mm256_sub_epi64(nodes, one), has);
    const __m256i memory = _mm256_maskload_epi64(reinterpret_cast<const long long*>(a.memory_cycles + q), in);
    for (int k = 0; k < count; ++k) {
      const auto* last_pass = reinterpret_cast<const long long*>(costs[k].last_pass_cycles.data());
      const __m256i last = _mm256_mask_i64gather_epi64(_mm256_setzero_si256(), last_pass, exit, has, 8);
      const __m256i passes = _mm256_add_epi64(_mm256_mul_epu32(before_last, quiet_cycles[k]), last);
      const __m256i cycles = _mm256_add_epi64(memory, _mm256_and_si256(passes, has));
      const __m256i flipped = _mm256_xor_si256(cycles, sign);
      const __m256i larger = _mm256_and_si256(_mm256_cmpgt_epi64(flipped, most[k]), in);
      most[k] = _mm256_blendv_epi8(most[k], flipped, larger);
    }
    quiet = _mm256_add_epi64(quiet, before_last);
    const __m256d has_pd = _mm256_castsi256_pd(has);
    with_nodes += static_cast<std::uint64_t>(__builtin_popcount(_mm256_movemask_pd(has_pd)));
    for (int j = 0; j < a.exits; ++j) {
      const __m256i is_j = _mm256_and_si256(_mm256_cmpeq_epi64(exit, _mm256_set1_epi64x(j)), has);
      const auto n = static_cast<std::uint64_t>(__builtin_popcount(_mm256_movemask_pd(_mm256_castsi256_pd(is_j))));
      tally.exit[j] += n;
      exiting += n;
    }
  }
  alignas(32) std::uint64_t quiets[4];
  _mm256_store_si256(reinterpret_cast<__m256i*>(quiets), quiet);
  tally.quiet += with_nodes - exiting + quiets[0] + quiets[1] + quiets[2] + quiets[3];
  for (int k = 0; k < count; ++k) {
    alignas(32) std::uint64_t lanes[4];
    _mm256_store_si256(reinterpret_cast<__m256i*>(lanes), _mm256_xor_si256(most[k], sign));
    slowest[k] = costs[k].once_cycles + std::max(std::max(lanes[0], lanes[1]), std::max(lanes[2], lanes[3]));
  }
}

RC_AVX512_WARNINGS_ON

#else

void SlowestRayQueriesLanes(const RayQueryArrays&, const RayPassCosts*, int, std::size_t, std::size_t, std::uint64_t*,
                            RayPassTally&) {
  throw std::logic_error("SlowestRayQueriesLanes: AVX-512 exists only on x86-64");
}

void SlowestRayQueriesAvx2(const RayQueryArrays&, const RayPassCosts*, int, std::size_t, std::size_t, std::uint64_t*,
                           RayPassTally&) {
  throw std::logic_error("SlowestRayQueriesAvx2: AVX2 exists only on x86-64");
}

#endif

void SlowestRayQueries(const RayQueryArrays& arrays, const RayPassCosts* costs, int count, std::size_t lo,
                       std::size_t hi, std::uint64_t* slowest, RayPassTally& tally) {
  if (UseAvx512()) return SlowestRayQueriesLanes(arrays, costs, count, lo, hi, slowest, tally);
  if (UseAvx2()) return SlowestRayQueriesAvx2(arrays, costs, count, lo, hi, slowest, tally);
  SlowestRayQueriesScalar(arrays, costs, count, lo, hi, slowest, tally);
}

}  // namespace rc
