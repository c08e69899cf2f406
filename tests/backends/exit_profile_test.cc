// The exit profile (ProfileExits, memory_replay.h) against its definition:
// per query, its passes without an exit first, then each exit value's
// passes in the order the query first reached it. Every query length from
// 0 to 130 passes, exit alphabets from one value to every byte, at 1 and 2
// threads (each thread tallies its own range of queries).
#include <algorithm>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <omp.h>

#include "backends/memory_replay.h"
#include "robocore/kernel_record.h"
#include "robocore/section_timing.h"

namespace rc {
namespace {

// (variant, passes) per query, straight from the definition.
std::vector<std::vector<std::pair<std::uint8_t, std::uint32_t>>> Definition(const KernelRecord& record) {
  std::vector<std::vector<std::pair<std::uint8_t, std::uint32_t>>> want(record.query_count());
  for (std::size_t q = 0; q < record.query_count(); ++q) {
    std::uint32_t quiet = 0;
    std::vector<std::pair<std::uint8_t, std::uint32_t>> exits;
    for (std::uint64_t i = record.fetch_offsets[q]; i < record.fetch_offsets[q + 1]; ++i) {
      const std::uint8_t e = record.node_exits[i];
      if (e == kNoExit) {
        ++quiet;
        continue;
      }
      bool found = false;
      for (auto& [variant, passes] : exits)
        if (variant == 1 + e) {
          ++passes;
          found = true;
        }
      if (!found) exits.emplace_back(static_cast<std::uint8_t>(1 + e), 1);
    }
    if (quiet > 0) want[q].emplace_back(0, quiet);
    want[q].insert(want[q].end(), exits.begin(), exits.end());
  }
  return want;
}

KernelRecord RecordOfExits(std::mt19937& rng, int alphabet) {
  KernelRecord record;
  record.fetch_offsets = {0};
  // Every length from 0 to 130 several times, in a shuffled order.
  std::vector<std::uint32_t> lengths;
  for (int repeat = 0; repeat < 4; ++repeat)
    for (std::uint32_t n = 0; n <= 130; ++n) lengths.push_back(n);
  std::shuffle(lengths.begin(), lengths.end(), rng);
  for (std::uint32_t n : lengths) {
    for (std::uint32_t k = 0; k < n; ++k) {
      const int draw = static_cast<int>(rng() % static_cast<unsigned>(alphabet + 1));
      record.node_exits.push_back(draw == alphabet ? kNoExit : static_cast<std::uint8_t>(draw));
    }
    record.fetch_offsets.push_back(record.node_exits.size());
  }
  return record;
}

TEST(ExitProfile, EqualsItsDefinitionAtEveryQueryLength) {
  std::mt19937 rng(11);
  const int threads_before = omp_get_max_threads();  // restored for the tests after this one
  // One exit value and "no exit", a few values (SACT's axes), and every
  // byte value but kNoExit.
  for (int alphabet : {1, 4, 16, 255}) {
    const KernelRecord record = RecordOfExits(rng, alphabet);
    const auto want = Definition(record);
    for (int threads : {1, 2}) {
      omp_set_num_threads(threads);
      const ExitProfile profile = ProfileExits(record);
      ASSERT_EQ(profile.offsets.size(), record.query_count() + 1);
      for (std::size_t q = 0; q < record.query_count(); ++q) {
        std::vector<std::pair<std::uint8_t, std::uint32_t>> got;
        for (std::uint32_t i = profile.offsets[q]; i < profile.offsets[q + 1]; ++i)
          got.emplace_back(profile.variant[i], profile.passes[i]);
        ASSERT_EQ(got, want[q]) << "query " << q << " of " << record.nodes(q) << " passes, alphabet " << alphabet
                                << ", " << threads << " threads";
      }
    }
  }
  omp_set_num_threads(threads_before);
}

}  // namespace
}  // namespace rc
