#include "backends/key_ranks.h"

#include <algorithm>
#include <stdexcept>
#include <type_traits>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include "common/cpu_features.h"

namespace rc {
namespace {

// One pass per key over all the keys: each key it precedes gains a place
// (vectorizes over the keys without a reduction per key).
template <class Key>
void CountSmaller(const Key* keys, std::size_t count, Key* place) {
  for (std::size_t i = 0; i < count; ++i) place[i] = 0;
  for (std::size_t j = 0; j < count; ++j) {
    const Key other = keys[j];
    for (std::size_t i = 0; i < count; ++i) place[i] += other < keys[i];
  }
}

void CheckCount(std::size_t count) {
  if (count > kMaxRankedKeys) throw std::invalid_argument("RankDistinctKeys: more than kMaxRankedKeys keys");
}

}  // namespace

void RankDistinctKeys(const std::uint64_t* keys, std::size_t count, std::uint64_t* place) {
  CheckCount(count);
  CountSmaller(keys, count, place);
}

void RankDistinctKeysPortable(const std::int32_t* keys, std::size_t count, std::int32_t* place) {
  CheckCount(count);
  CountSmaller(keys, count, place);
}

#if defined(__x86_64__)
namespace {

// The keys stay in kVectors registers while each key is compared with all
// of them. The vector count is a template argument so that the per-vector
// arrays live in registers: with a run-time count they were kept on the
// stack, and each count waited on its own previous store.
template <int kVectors>
__attribute__((target("avx512f"))) void RankAvx512(const std::int32_t* keys, std::size_t count, std::int32_t* place) {
  __m512i key[kVectors], at[kVectors];
  __mmask16 in[kVectors];
  for (int v = 0; v < kVectors; ++v) {
    const std::size_t left = count - 16 * static_cast<std::size_t>(v);
    in[v] = static_cast<__mmask16>(left >= 16 ? 0xFFFF : (1u << left) - 1);
    key[v] = _mm512_maskz_loadu_epi32(in[v], keys + 16 * v);
    at[v] = _mm512_setzero_si512();
  }
  const __m512i one = _mm512_set1_epi32(1);
  for (std::size_t j = 0; j < count; ++j) {
    const __m512i other = _mm512_set1_epi32(keys[j]);
    for (int v = 0; v < kVectors; ++v)
      at[v] = _mm512_mask_add_epi32(at[v], _mm512_cmpgt_epi32_mask(key[v], other), at[v], one);
  }
  for (int v = 0; v < kVectors; ++v) _mm512_mask_storeu_epi32(place + 16 * v, in[v], at[v]);
}

// The same in AVX2, kVectors registers of eight keys (the keys padded to
// whole registers); a comparison's all-ones lanes are -1, so subtracting
// them counts.
template <int kVectors>
__attribute__((target("avx2"))) void RankAvx2(const std::int32_t* keys, std::size_t count, std::int32_t* place) {
  alignas(32) std::int32_t padded[8 * kVectors] = {};
  std::copy(keys, keys + count, padded);
  __m256i key[kVectors], at[kVectors];
  for (int v = 0; v < kVectors; ++v) {
    key[v] = _mm256_load_si256(reinterpret_cast<const __m256i*>(padded + 8 * v));
    at[v] = _mm256_setzero_si256();
  }
  for (std::size_t j = 0; j < count; ++j) {
    const __m256i other = _mm256_set1_epi32(keys[j]);
    for (int v = 0; v < kVectors; ++v) at[v] = _mm256_sub_epi32(at[v], _mm256_cmpgt_epi32(key[v], other));
  }
  for (int v = 0; v < kVectors; ++v) _mm256_store_si256(reinterpret_cast<__m256i*>(padded + 8 * v), at[v]);
  std::copy(padded, padded + count, place);
}

// Calls rank(std::integral_constant<int, vectors>{}), for 1 <= vectors <=
// kMax: the run-time vector count as the template argument the forms above
// take.
template <int kMax, class Rank>
void WithVectorCount(std::size_t vectors, Rank rank) {
  if constexpr (kMax > 1) {
    if (vectors < static_cast<std::size_t>(kMax)) return WithVectorCount<kMax - 1>(vectors, rank);
  }
  rank(std::integral_constant<int, kMax>{});
}

// Checks the count, then ranks `count` keys with rank(vectors) in registers
// of kPerVector keys each.
template <int kPerVector, class Rank>
void RankInVectors(std::size_t count, Rank rank) {
  static_assert(kMaxRankedKeys % kPerVector == 0, "whole registers of keys");
  CheckCount(count);
  if (count > 0)
    WithVectorCount<static_cast<int>(kMaxRankedKeys / kPerVector)>((count + kPerVector - 1) / kPerVector, rank);
}

}  // namespace

__attribute__((target("avx512f"))) void RankDistinctKeysAvx512(const std::int32_t* keys, std::size_t count,
                                                               std::int32_t* place) {
  RankInVectors<16>(count, [&](auto vectors) { RankAvx512<decltype(vectors)::value>(keys, count, place); });
}

__attribute__((target("avx2"))) void RankDistinctKeysAvx2(const std::int32_t* keys, std::size_t count,
                                                          std::int32_t* place) {
  RankInVectors<8>(count, [&](auto vectors) { RankAvx2<decltype(vectors)::value>(keys, count, place); });
}
#else
void RankDistinctKeysAvx512(const std::int32_t*, std::size_t, std::int32_t*) {
  throw std::logic_error("RankDistinctKeysAvx512: AVX-512 exists only on x86-64");
}
void RankDistinctKeysAvx2(const std::int32_t*, std::size_t, std::int32_t*) {
  throw std::logic_error("RankDistinctKeysAvx2: AVX2 exists only on x86-64");
}
#endif

void RankDistinctKeys(const std::int32_t* keys, std::size_t count, std::int32_t* place) {
  if (UseAvx512())
    RankDistinctKeysAvx512(keys, count, place);
  else if (UseAvx2())
    RankDistinctKeysAvx2(keys, count, place);
  else
    RankDistinctKeysPortable(keys, count, place);
}

}  // namespace rc
