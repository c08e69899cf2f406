#pragma once
// The rank of each of a few distinct keys (a warp's lanes): the number of
// keys smaller than it, found by counting rather than sorting. For at most
// kMaxRankedKeys keys, counting costs count^2 comparisons that run in SIMD
// lanes with no branch to mispredict, which beats a sort at warp sizes.
// Every form gives the same ranks (tests/backends/key_ranks_test.cc).
#include <cstddef>
#include <cstdint>

namespace rc {

inline constexpr std::size_t kMaxRankedKeys = 64;  // GpuParams::warp_size's upper bound

// place[i] = how many of keys[0, count) are smaller than keys[i]; count at
// most kMaxRankedKeys, keys distinct. 32-bit keys take the widest SIMD
// form the suite uses (AVX-512, AVX2; UseAvx512(), common/cpu_features.h).
void RankDistinctKeys(const std::uint64_t* keys, std::size_t count, std::uint64_t* place);
void RankDistinctKeys(const std::int32_t* keys, std::size_t count, std::int32_t* place);

// The portable form of the 32-bit ranks, the AVX-512 one (only where
// CpuHasAvx512(), common/cpu_features.h) and the AVX2 one (only where
// CpuHasAvx2()). RankDistinctKeys takes the widest in use.
void RankDistinctKeysPortable(const std::int32_t* keys, std::size_t count, std::int32_t* place);
void RankDistinctKeysAvx512(const std::int32_t* keys, std::size_t count, std::int32_t* place);
void RankDistinctKeysAvx2(const std::int32_t* keys, std::size_t count, std::int32_t* place);

}  // namespace rc
