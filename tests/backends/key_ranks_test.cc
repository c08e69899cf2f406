// Ranks of distinct keys (key_ranks.h): every form against a sort, at every
// count up to the limit (the SIMD forms' partial registers included).
#include "backends/key_ranks.h"

#include <algorithm>
#include <numeric>
#include <random>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "common/cpu_features.h"

namespace rc {
namespace {

// The ranks by sorting: the keys' indices in key order.
template <class Key>
std::vector<Key> SortedRanks(const std::vector<Key>& keys) {
  std::vector<std::size_t> order(keys.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return keys[a] < keys[b]; });
  std::vector<Key> rank(keys.size());
  for (std::size_t r = 0; r < order.size(); ++r) rank[order[r]] = static_cast<Key>(r);
  return rank;
}

TEST(KeyRanks, EveryFormRanksLikeASort) {
  std::mt19937 rng(5);
  for (std::size_t count = 0; count <= kMaxRankedKeys; ++count) {
    // (node count, lane) keys as the replay builds them, some negative-free
    // and some near the signed 32-bit limit.
    std::vector<std::int32_t> narrow(count);
    std::vector<std::uint64_t> wide(count);
    for (std::size_t i = 0; i < count; ++i) {
      const std::uint32_t nodes = count % 3 == 0 ? (1u << 24) + rng() % 1000 : rng() % 40;
      narrow[i] = static_cast<std::int32_t>(nodes << 6 | i);
      wide[i] = std::uint64_t{rng()} << 6 | i;
    }
    const std::vector<std::int32_t> want = SortedRanks(narrow);
    std::vector<std::int32_t> got(count);
    RankDistinctKeysPortable(narrow.data(), count, got.data());
    EXPECT_EQ(got, want) << count;
    RankDistinctKeys(narrow.data(), count, got.data());
    EXPECT_EQ(got, want) << count;
    if (CpuHasAvx512()) {
      std::fill(got.begin(), got.end(), -1);
      RankDistinctKeysAvx512(narrow.data(), count, got.data());
      EXPECT_EQ(got, want) << count;
    }
    if (CpuHasAvx2()) {
      std::fill(got.begin(), got.end(), -1);
      RankDistinctKeysAvx2(narrow.data(), count, got.data());
      EXPECT_EQ(got, want) << count;
    }
    std::vector<std::uint64_t> wide_got(count);
    RankDistinctKeys(wide.data(), count, wide_got.data());
    EXPECT_EQ(wide_got, SortedRanks(wide)) << count;
  }
  if (!CpuHasAvx512())
    GTEST_SKIP() << "this host has no AVX-512: the portable form" << (CpuHasAvx2() ? " and AVX2" : "")
                 << " were checked";
}

TEST(KeyRanks, RefusesMoreKeysThanTheLimit) {
  std::vector<std::int32_t> keys(kMaxRankedKeys + 1), place(kMaxRankedKeys + 1);
  std::iota(keys.begin(), keys.end(), 0);
  EXPECT_THROW(RankDistinctKeysPortable(keys.data(), keys.size(), place.data()), std::invalid_argument);
}

}  // namespace
}  // namespace rc
