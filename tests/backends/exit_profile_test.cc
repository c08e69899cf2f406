// The exit profile (ProfileExits, memory_replay.h) against its definition:
// per query, its passes without an exit first, then each exit value's
// passes in the order the query first reached it. Every query length from
// 0 to 130 passes, exit alphabets from one value to every byte, at 1 and 2
// threads (each thread tallies its own range of queries). And a collision
// batch's record with its exits tallied as it is built, against its
// per-fetch record.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <omp.h>

#include "backends/backend.h"
#include "backends/memory_replay.h"
#include "robocore/collision/box_tree.h"
#include "robocore/collision/sact_kernel_record.h"
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

// SactKernelRecord with RecordedExits::kTallied: the same record but for
// the form of its exits, which equal ProfileExits of the per-fetch record,
// so every backend prices the two alike (with every address kept and with
// a sample).
TEST(ExitProfile, ACollisionRecordTalliedAsBuiltPricesAsItsPerFetchRecord) {
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> coordinate(-5.0, 5.0), size(0.05, 0.6), angle(-M_PI, M_PI);
  std::vector<Aabbd> boxes(120);
  for (Aabbd& b : boxes) {
    b.centre = Eigen::Vector3d(coordinate(rng), coordinate(rng), coordinate(rng));
    b.half = Eigen::Vector3d(size(rng), size(rng), size(rng));
  }
  const FlatBoxTree<double> tree(BuildMedianSplitTree(boxes));
  std::vector<Obbd> obbs(3000);
  for (Obbd& o : obbs) {
    o.centre = Eigen::Vector3d(coordinate(rng), coordinate(rng), coordinate(rng));
    o.half = Eigen::Vector3d(size(rng), size(rng), size(rng));
    o.axes = (Eigen::AngleAxisd(angle(rng), Eigen::Vector3d::UnitZ()) *
              Eigen::AngleAxisd(angle(rng), Eigen::Vector3d::UnitX()))
                 .toRotationMatrix();
  }
  const CollisionBatch batch = CollideBatch(tree, obbs, CollisionOptions<double>{});
  AddressSample sampled;
  sampled.sampled_sms = 1;
  const BackendParameters params;
  for (const AddressSample& sample : {AddressSample{}, sampled}) {
    const KernelRecord per_fetch = SactKernelRecord(batch, nullptr, sample);
    const KernelRecord tallied = SactKernelRecord(batch, nullptr, sample, RecordedExits::kTallied);
    ASSERT_FALSE(per_fetch.exits_tallied());
    ASSERT_TRUE(tallied.exits_tallied());
    EXPECT_TRUE(tallied.node_exits.empty());
    const ExitProfile expected = ProfileExits(per_fetch);
    EXPECT_GT(expected.variant.size(), per_fetch.query_count());  // queries with quiet passes and an exit
    EXPECT_EQ(tallied.tallied_exits->offsets, expected.offsets);
    EXPECT_EQ(tallied.tallied_exits->variant, expected.variant);
    EXPECT_EQ(tallied.tallied_exits->passes, expected.passes);
    EXPECT_EQ(tallied.fetch_offsets, per_fetch.fetch_offsets);
    EXPECT_EQ(tallied.fetch_addresses, per_fetch.fetch_addresses);
    EXPECT_EQ(tallied.address_offsets, per_fetch.address_offsets);
    EXPECT_EQ(tallied.touched_sectors, per_fetch.touched_sectors);
    EXPECT_EQ(sample.KeepsAll(), per_fetch.touched_sectors == 0);
    for (const std::string& name : Backend::ModelledNames()) {
      const auto backend = Backend::Create(name, params);
      const BatchCost a = backend->Price(per_fetch), b = backend->Price(tallied);
      EXPECT_EQ(a.cycles, b.cycles) << name;
      EXPECT_EQ(a.micro_ops, b.micro_ops) << name;
      EXPECT_EQ(a.memory.sector_requests, b.memory.sector_requests) << name;
      EXPECT_EQ(a.ctrl_exits, b.ctrl_exits) << name;
    }
  }
}

}  // namespace
}  // namespace rc
