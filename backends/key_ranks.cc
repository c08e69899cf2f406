#include "backends/key_ranks.h"

#include <algorithm>
#include <stdexcept>

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
// The keys stay in four registers while each key is compared with all of
// them.
__attribute__((target("avx512f"))) void RankDistinctKeysAvx512(const std::int32_t* keys, std::size_t count,
                                                               std::int32_t* place) {
  CheckCount(count);
  constexpr int kVectors = static_cast<int>(kMaxRankedKeys / 16);
  __m512i key[kVectors], at[kVectors];
  __mmask16 in[kVectors];
  const int vectors = static_cast<int>((count + 15) / 16);
  for (int v = 0; v < vectors; ++v) {
    const std::size_t left = count - 16 * static_cast<std::size_t>(v);
    in[v] = static_cast<__mmask16>(left >= 16 ? 0xFFFF : (1u << left) - 1);
    key[v] = _mm512_maskz_loadu_epi32(in[v], keys + 16 * v);
    at[v] = _mm512_setzero_si512();
  }
  const __m512i one = _mm512_set1_epi32(1);
  for (std::size_t j = 0; j < count; ++j) {
    const __m512i other = _mm512_set1_epi32(keys[j]);
    for (int v = 0; v < vectors; ++v)
      at[v] = _mm512_mask_add_epi32(at[v], _mm512_cmpgt_epi32_mask(key[v], other), at[v], one);
  }
  for (int v = 0; v < vectors; ++v) _mm512_mask_storeu_epi32(place + 16 * v, in[v], at[v]);
}

// The same in AVX2: eight registers of eight keys; a comparison's all-ones
// lanes are -1, so subtracting them counts.
__attribute__((target("avx2"))) void RankDistinctKeysAvx2(const std::int32_t* keys, std::size_t count,
                                                          std::int32_t* place) {
  CheckCount(count);
  constexpr int kVectors = static_cast<int>(kMaxRankedKeys / 8);
  alignas(32) std::int32_t padded[kMaxRankedKeys] = {};
  std::copy(keys, keys + count, padded);
  __m256i key[kVectors], at[kVectors];
  const int vectors = static_cast<int>((count + 7) / 8);
  for (int v = 0; v < vectors; ++v) {
    key[v] = _mm256_load_si256(reinterpret_cast<const __m256i*>(padded + 8 * v));
    at[v] = _mm256_setzero_si256();
  }
  for (std::size_t j = 0; j < count; ++j) {
    const __m256i other = _mm256_set1_epi32(keys[j]);
    for (int v = 0; v < vectors; ++v) at[v] = _mm256_sub_epi32(at[v], _mm256_cmpgt_epi32(key[v], other));
  }
  for (int v = 0; v < vectors; ++v) _mm256_store_si256(reinterpret_cast<__m256i*>(padded + 8 * v), at[v]);
  std::copy(padded, padded + count, place);
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
