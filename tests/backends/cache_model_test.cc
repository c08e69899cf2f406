// The cache hierarchy: the footprint picks the detail (cold vs LRU), LRU
// order in the fully associative L1 and the set-associative L2, sector
// granularity, and latencies.
#include <algorithm>
#include <list>

#include <gtest/gtest.h>

#include "backends/cache_model.h"
#include "common/random_stream.h"

namespace rc {
namespace {

constexpr std::uint64_t kBase = std::uint64_t{1} << 32;

TEST(CacheHierarchy, FootprintDecidesTheModel) {
  const GpuParams gpu;
  // 400 x 300 one-byte cells = 117 KiB: more than the 64 KiB L1.
  CacheHierarchy office(gpu, kBase, kBase + 400 * 300);
  EXPECT_EQ(office.l1_model().rfind("lru", 0), 0u);
  EXPECT_EQ(office.l2_model().rfind("cold", 0), 0u);
  CacheHierarchy small(gpu, kBase, kBase + 256 * 256);
  EXPECT_EQ(small.l1_model().rfind("cold", 0), 0u);
  CacheHierarchy wean_field(gpu, kBase, kBase + 800 * 800 * 4);  // 2.4 MiB distance field
  EXPECT_EQ(wean_field.l2_model().rfind("cold", 0), 0u);
  CacheHierarchy huge(gpu, kBase, kBase + 4 * 1024 * 1024);
  EXPECT_EQ(huge.l2_model().rfind("lru", 0), 0u);
}

TEST(CacheHierarchy, LatenciesAddUpLevelByLevel) {
  const GpuParams gpu;
  CacheHierarchy c(gpu, kBase, kBase + 1024);
  EXPECT_EQ(c.LatencyCycles(MemoryLevel::kL1), 20);
  EXPECT_EQ(c.LatencyCycles(MemoryLevel::kL2), 180);
  // DRAM: (100 + 20) DRAM cycles at 3500 MHz = 47 core cycles at 1365 MHz.
  EXPECT_EQ(gpu.DramExtraCycles(), 47);
  EXPECT_EQ(c.LatencyCycles(MemoryLevel::kDram), 227);
  EXPECT_EQ(c.Access(0, kBase), MemoryLevel::kDram);
  EXPECT_EQ(c.Access(0, kBase + 31), MemoryLevel::kL1);    // same sector
  EXPECT_EQ(c.Access(1, kBase), MemoryLevel::kL2);         // another SM's L1
  EXPECT_EQ(c.Access(0, kBase + 32), MemoryLevel::kDram);  // next sector: sectors fill one by one
}

TEST(CacheHierarchy, FullyAssociativeL1EvictsTheLeastRecentlyUsedLine) {
  GpuParams gpu;
  gpu.l1_bytes = 2 * gpu.line_bytes;  // two lines
  CacheHierarchy c(gpu, kBase, kBase + 10 * 128);
  auto line = [](int i) { return kBase + 128 * static_cast<std::uint64_t>(i); };
  c.Access(0, line(0));
  c.Access(0, line(1));
  EXPECT_EQ(c.Access(0, line(0)), MemoryLevel::kL1);  // order now 0, 1
  c.Access(0, line(2));                               // evicts 1
  EXPECT_EQ(c.Access(0, line(0)), MemoryLevel::kL1);
  EXPECT_EQ(c.Access(0, line(1)), MemoryLevel::kL2);  // was evicted; evicts 2
  EXPECT_EQ(c.Access(0, line(2)), MemoryLevel::kL2);
}

TEST(CacheHierarchy, SetAssociativeL2EvictsWithinASet) {
  GpuParams gpu;
  gpu.l1_bytes = gpu.line_bytes;  // one line: almost everything misses L1
  gpu.l2_ways = 2;
  gpu.l2_bytes = 2 * 2 * gpu.line_bytes;  // 2 sets x 2 ways
  CacheHierarchy c(gpu, kBase, kBase + 16 * 128);
  auto line = [](int i) { return kBase + 128 * static_cast<std::uint64_t>(i); };
  EXPECT_EQ(c.Access(0, line(0)), MemoryLevel::kDram);
  EXPECT_EQ(c.Access(0, line(2)), MemoryLevel::kDram);  // set 0
  EXPECT_EQ(c.Access(0, line(1)), MemoryLevel::kDram);  // set 1: no eviction in set 0
  EXPECT_EQ(c.Access(0, line(0)), MemoryLevel::kL2);
  EXPECT_EQ(c.Access(0, line(4)), MemoryLevel::kDram);  // set 0 full: evicts line 2
  EXPECT_EQ(c.Access(0, line(0)), MemoryLevel::kL2);
  EXPECT_EQ(c.Access(0, line(2)), MemoryLevel::kDram);
}

// Property: the L1 (timestamp LRU, by level or through the hierarchy) agrees with a
// plain list LRU of lines with sector masks on random streams with reuse.
// Hit (1) or miss (0) of each access of `stream` (sectors) in a fully
// associative LRU cache of `capacity` lines, sector-filled: a list.
std::vector<std::uint8_t> ReferenceLru(const std::vector<std::uint32_t>& stream, int sectors_per_line,
                                       std::size_t capacity) {
  std::list<std::pair<int, unsigned>> lru;  // (line, sector mask), most recent first
  std::vector<std::uint8_t> expected;
  for (std::uint32_t sector : stream) {
    const int line = static_cast<int>(sector) / sectors_per_line;
    const unsigned bit = 1u << (sector % sectors_per_line);
    auto it = std::find_if(lru.begin(), lru.end(), [&](const auto& e) { return e.first == line; });
    bool hit = false;
    unsigned mask = bit;
    if (it != lru.end()) {
      hit = it->second & bit;
      mask |= it->second;
      lru.erase(it);
    } else if (lru.size() == capacity) {
      lru.pop_back();
    }
    lru.emplace_front(line, mask);
    expected.push_back(hit);
  }
  return expected;
}

// Mostly near recent lines, sometimes anywhere (hits and evictions), each
// line chosen for a run of 1 to `max_run` accesses to its sectors (a run
// repeats the most recently used line). Long enough that the history is
// compacted several times.
std::vector<std::uint32_t> LineStream(int lines, int sectors_per_line, int max_run, std::uint64_t seed) {
  RandomStream s(seed, StreamPurpose::kTest, 0, 0);
  std::vector<std::uint32_t> stream;
  while (stream.size() < 100000) {
    const int line = s.Uniform() < 0.8 ? static_cast<int>(s.Uniform() * 20) : static_cast<int>(s.Uniform() * lines);
    const int run = max_run > 1 ? 1 + static_cast<int>(s.Uniform() * max_run) : 1;
    for (int k = 0; k < run; ++k)
      stream.push_back(
          static_cast<std::uint32_t>(line * sectors_per_line + static_cast<int>(s.Uniform() * sectors_per_line)));
  }
  return stream;
}

// A 16-line L1 (fully associative: the footprint of 64 lines exceeds it),
// a LineStream over the footprint and the reference's answers.
struct LruCase {
  GpuParams gpu;
  int lines = 64;
  std::vector<std::uint32_t> stream;
  std::vector<std::uint8_t> expected;
};
LruCase MakeLruCase(int max_run, std::uint64_t seed) {
  LruCase c;
  c.gpu.l1_bytes = 16 * c.gpu.line_bytes;
  const int sectors_per_line = c.gpu.line_bytes / c.gpu.sector_bytes;
  c.stream = LineStream(c.lines, sectors_per_line, max_run, seed);
  c.expected = ReferenceLru(c.stream, sectors_per_line, 16);
  return c;
}

TEST(CacheHierarchy, L1AgreesWithAReferenceLruOnRandomStreams) {
  const LruCase c = MakeLruCase(1, 17);
  const GpuParams& gpu = c.gpu;
  const int lines = c.lines;
  const std::vector<std::uint32_t>& stream = c.stream;
  const std::vector<std::uint8_t>& expected = c.expected;
  CacheHierarchy levels(gpu, kBase, kBase + lines * 128);
  std::vector<std::uint8_t> got(stream.size());
  for (std::size_t i = 0; i < stream.size(); ++i) got[i] = levels.L1(0).Access(stream[i]);
  EXPECT_EQ(got, expected);
  CacheHierarchy single(gpu, kBase, kBase + lines * 128);
  int mismatches = 0;
  for (std::size_t i = 0; i < stream.size(); ++i)
    mismatches += (single.Access(0, kBase + std::uint64_t{stream[i]} * 32) == MemoryLevel::kL1) != (expected[i] != 0);
  EXPECT_EQ(mismatches, 0);
  EXPECT_GT(std::count(expected.begin(), expected.end(), 0), 1000);  // evictions happened
}

// Runs of accesses to one line (the most recently used, again and again,
// as neighbouring rays fetch), driven through AccessAll in waves of 1 to
// 300 accesses as the replay drives it; a wave's first access may repeat
// the previous wave's last line.
TEST(CacheHierarchy, L1AgreesWithAReferenceLruOnRunsOfRepeatsInWaves) {
  const LruCase c = MakeLruCase(6, 23);
  const std::vector<std::uint32_t>& stream = c.stream;
  const std::vector<std::uint8_t>& expected = c.expected;
  CacheHierarchy levels(c.gpu, kBase, kBase + c.lines * 128);
  std::vector<std::uint8_t> got(stream.size(), 1);
  std::vector<std::uint32_t> misses(stream.size());
  RandomStream waves(29, StreamPurpose::kTest, 0, 0);
  for (std::size_t lo = 0; lo < stream.size();) {
    const std::size_t n = std::min(stream.size() - lo, 1 + static_cast<std::size_t>(waves.Uniform() * 300));
    const std::size_t m = levels.L1(0).AccessAll(stream.data() + lo, n, misses.data());
    for (std::size_t j = 0; j < m; ++j) got[lo + misses[j]] = 0;
    lo += n;
  }
  EXPECT_EQ(got, expected);
  EXPECT_GT(std::count(expected.begin(), expected.end(), 0), 1000);  // evictions happened
}

}  // namespace
}  // namespace rc
