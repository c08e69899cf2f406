#include "backends/key_ranks.h"

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
#else
void RankDistinctKeysAvx512(const std::int32_t*, std::size_t, std::int32_t*) {
  throw std::logic_error("RankDistinctKeysAvx512: AVX-512 exists only on x86-64");
}
#endif

void RankDistinctKeys(const std::int32_t* keys, std::size_t count, std::int32_t* place) {
  if (CpuHasAvx512())
    RankDistinctKeysAvx512(keys, count, place);
  else
    RankDistinctKeysPortable(keys, count, place);
}

}  // namespace rc
