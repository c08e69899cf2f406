// Kernel records: the recorded batch gives the CPU reference's hits, its
// addresses are the structures' bases plus index * element size, the exits
// follow the ray programs' contract, it does not depend on the thread
// count, and Validate catches inconsistent records. Also the RoboCore API
// facade.
#include <omp.h>

#include <algorithm>
#include <atomic>
#include <set>
#include <string>
#include <tuple>
#include <utility>

#include <gtest/gtest.h>

#include "robocore/ray_batch_lanes.h"
#include "robocore/ray_batch_recorded.h"
#include "robocore/ray_lane_state.h"
#include "robocore/robocore_api.h"
#include "robocore/shipped_programs.h"
#include "support/simd_levels.h"
#include "test_scenes.h"

namespace rc {
namespace {

// The node indices the scalar kernel visits for query q, in its order.
std::vector<std::uint32_t> ScalarVisits(const RayCastScene& scene, const RayBatch& batch, std::size_t q) {
  struct IndexVisitor {
    std::vector<std::uint32_t> indices;
    void Fetch(FetchKind, std::uint32_t index) { indices.push_back(index); }
  } visitor;
  const RayQuery& query = batch.queries[q];
  CastRay(scene, query.origin_x_m, query.origin_y_m, query.angle_rad, batch.max_range_m, visitor);
  return visitor.indices;
}

class RecordTest : public ::testing::TestWithParam<RayCastMethod> {};

TEST_P(RecordTest, HitsNodesAddressesAndExitsMatchTheKernel) {
  const OccupancyGrid grid = test::RoomGrid(90, 70, 0.1, 0.04, 5);
  const RayCastScene scene(grid, GetParam());
  const RayBatch batch = test::FanBatch(grid, 30, 37, 6.0, 6);
  std::vector<RayHit> reference, hits;
  CastRayBatch(scene, batch, reference);
  KernelRecord record;
  CastRayBatchRecorded(scene, batch, hits, record);
  ASSERT_NO_THROW(record.Validate());
  ASSERT_EQ(record.query_count(), batch.queries.size());
  ASSERT_EQ(record.regions.size(), 1u);
  const MemoryRegion& region = record.regions[0];
  EXPECT_EQ(region.element_bytes, GetParam() == RayCastMethod::kRayMarching ? 4u : 1u);
  EXPECT_EQ(region.base % DeviceLayout{}.alignment, 0u);
  int hit_exits = 0;
  for (std::size_t i = 0; i < hits.size(); ++i) {
    ASSERT_EQ(hits[i].range_m, reference[i].range_m) << i;
    ASSERT_EQ(hits[i].nodes, reference[i].nodes) << i;
    ASSERT_EQ(record.nodes(i), hits[i].nodes) << i;
    const std::uint64_t lo = record.fetch_offsets[i], hi = record.fetch_offsets[i + 1];
    for (std::uint64_t f = lo; f < hi; ++f) {
      const std::uint64_t index = (record.fetch_addresses[f] - region.base) / region.element_bytes;
      ASSERT_EQ((record.fetch_addresses[f] - region.base) % region.element_bytes, 0u);
      ASSERT_LT(index, grid.cell_count());
      const auto k = static_cast<std::uint32_t>(f - lo);
      if (f + 1 < hi) {
        ASSERT_EQ(record.ExitAt(i, k), kNoExit);
      } else {
        const bool stops = grid.cells()[index] != CellState::kFree;
        ASSERT_EQ(record.ExitAt(i, k), stops ? kRayHitReturn : kRayEndReturn) << i;
        hit_exits += stops;
      }
    }
  }
  EXPECT_GT(hit_exits, 0);
  EXPECT_EQ(record.program->name(), ToString(StepProgramFor(GetParam())));
  EXPECT_EQ(record.leaf_kind, LeafProgramKind::kBeamModel);
}

// The recorded addresses are the nodes the scalar kernel visits, in its
// order, for a full record and for a sample's kept queries (cast in SIMD
// lanes where the CPU has them, which log each lane's node indices).
TEST_P(RecordTest, AddressesAreTheNodesTheScalarKernelVisits) {
  const OccupancyGrid grid = test::RoomGrid(80, 64, 0.1, 0.05, 3);
  const RayCastScene scene(grid, GetParam());
  const RayBatch batch = test::FanBatch(grid, 90, 41, 5.5, 4);  // 3690 queries: blocks of 256 on 8 SMs
  for (const auto& [sampled_sms, block_stride] : {std::pair{0, 1}, std::pair{1, 1}, std::pair{3, 1}, std::pair{1, 2}}) {
    RecordOptions options;
    if (sampled_sms > 0) options.sample.sampled_sms = sampled_sms;
    options.sample.block_stride = block_stride;
    std::vector<RayHit> hits;
    KernelRecord record;
    CastRayBatchRecorded(scene, batch, hits, record, options);
    const MemoryRegion& region = record.regions[0];
    std::size_t kept = 0;
    for (std::size_t q = 0; q < batch.queries.size(); ++q) {
      if (!record.KeepsAddresses(q)) continue;
      const std::vector<std::uint32_t> visits = ScalarVisits(scene, batch, q);
      ASSERT_EQ(visits.size(), record.nodes(q)) << sampled_sms << " " << q;
      for (std::uint32_t k = 0; k < record.nodes(q); ++k)
        ASSERT_EQ(record.addresses(q)[k], region.base + std::uint64_t{visits[k]} * region.element_bytes)
            << sampled_sms << " " << q << " " << k;
      ++kept;
    }
    EXPECT_GT(kept, 0u) << sampled_sms;
  }
}

// A sample's count of the sectors the whole batch touched is the scalar
// kernel's, and so are the last exits, on a map large enough that few rays
// cover it: a lane whose ray has ended steps on past its end until the
// lanes run dry, and must not count what it steps through (it once did,
// which made the priced cycles depend on whether the CPU has AVX-512).
TEST_P(RecordTest, TouchedSectorsAndExitsAreTheScalarKernels) {
  const OccupancyGrid grid = test::RoomGrid(400, 300, 0.05, 0.01, 11);
  const RayCastScene scene(grid, GetParam());
  const RayBatch batch = test::FanBatch(grid, 70, 30, 8.0, 12);
  RecordOptions options;
  options.sample.sampled_sms = 1;
  std::vector<RayHit> hits;
  KernelRecord record;
  CastRayBatchRecorded(scene, batch, hits, record, options);
  const MemoryRegion& region = record.regions[0];
  std::set<std::uint64_t> sectors;
  for (std::size_t q = 0; q < batch.queries.size(); ++q) {
    const std::vector<std::uint32_t> visits = ScalarVisits(scene, batch, q);
    for (std::uint32_t index : visits)
      sectors.insert((region.base - record.footprint_begin() + std::uint64_t{index} * region.element_bytes) / 32);
    std::uint8_t exit = kNoExit;
    if (!visits.empty()) {
      const std::uint32_t last = visits.back();
      const bool stops = GetParam() == RayCastMethod::kRayMarching ? scene.distance_field()->values()[last] == 0.0f
                                                                   : grid.cells()[last] != CellState::kFree;
      exit = stops ? kRayHitReturn : kRayEndReturn;
    }
    ASSERT_EQ(record.last_exits[q], exit) << q;
  }
  EXPECT_EQ(record.touched_sectors, sectors.size());
}

// The lanes find a fetched cell's sector with a 32-bit shift where the
// structure starts on a sector, and in 64 bits where it does not (AVX-512),
// or one lane at a time (AVX2): every instruction set this CPU runs marks
// exactly the sectors of the cells the scalar kernel visits. The batch
// fetches more nodes than AVX-512's queue of sectors holds, so the queue is
// marked both when full and at the end.
TEST_P(RecordTest, TheLanesMarkTheVisitedCellsSectorsAtAnyOffset) {
  const OccupancyGrid grid = test::RoomGrid(200, 150, 0.05, 0.01, 5);
  const RayCastScene scene(grid, GetParam());
  if (!RayLanesApply(scene)) GTEST_SKIP() << "this host runs no lanes (neither AVX2 nor AVX-512)";
  const RayBatch batch = test::FanBatch(grid, 40, 30, 6.0, 3);
  const std::uint32_t element_bytes = GetParam() == RayCastMethod::kRayMarching ? 4 : 2;
  for (RayLaneIsa isa : HostRayLaneIsas())
    for (std::uint64_t offset : {std::uint64_t{0}, std::uint64_t{4096}, std::uint64_t{8}, std::uint64_t{4100}}) {
      std::set<std::uint64_t> expected;
      for (std::size_t q = 0; q < batch.queries.size(); ++q)
        for (std::uint32_t index : ScalarVisits(scene, batch, q))
          expected.insert((offset + std::uint64_t{index} * element_bytes) / 32);
      std::vector<std::uint8_t> touched((offset + grid.cell_count() * element_bytes) / 32 + 1, 0);
      LaneRecording rec;
      rec.touched = touched.data();
      rec.offset = offset;
      rec.element_bytes = element_bytes;
      rec.sector_shift = 5;
      std::vector<RayHit> hits(batch.queries.size());
      CastRayLanesIn(isa, scene, batch.queries.data(), batch.queries.size(), batch.max_range_m, hits.data(), &rec);
      std::set<std::uint64_t> marked;
      for (std::size_t s = 0; s < touched.size(); ++s)
        if (touched[s] != 0) marked.insert(s);
      EXPECT_EQ(marked, expected) << ToString(isa) << ", offset " << offset;
      std::size_t fetches = 0;
      for (const RayHit& hit : hits) fetches += hit.nodes;
      EXPECT_GT(fetches, 2 * ray_lanes::SectorQueue::kCapacity);
    }
}

// Every instruction set this CPU runs logs each query's nodes as the scalar
// kernel visits them: the lanes' buffers grow from a small first size during
// the first call, and a second, smaller call reuses them (entries past a
// lane's last query are scratch, not nodes).
TEST_P(RecordTest, TheLanesLogTheNodesTheScalarKernelVisits) {
  const OccupancyGrid grid = test::RoomGrid(200, 150, 0.05, 0.01, 6);
  const RayCastScene scene(grid, GetParam());
  if (!RayLanesApply(scene)) GTEST_SKIP() << "this host runs no lanes (neither AVX2 nor AVX-512)";
  const RayBatch batch = test::FanBatch(grid, 40, 30, 6.0, 4);
  for (RayLaneIsa isa : HostRayLaneIsas()) {
    LaneNodeLog log;
    for (const std::size_t count : {batch.queries.size(), batch.queries.size() / 3}) {
      LaneRecording rec;
      rec.nodes = &log;
      std::vector<RayHit> hits(count);
      CastRayLanesIn(isa, scene, batch.queries.data(), count, batch.max_range_m, hits.data(), &rec);
      for (std::size_t q = 0; q < count; ++q) {
        const std::vector<std::uint32_t> visits = ScalarVisits(scene, batch, q);
        ASSERT_EQ(hits[q].nodes, visits.size()) << ToString(isa) << ", query " << q;
        const std::vector<std::uint32_t> logged(log.NodesOf(q), log.NodesOf(q) + hits[q].nodes);
        ASSERT_EQ(logged, visits) << ToString(isa) << ", " << count << " queries, query " << q;
      }
    }
  }
}

TEST_P(RecordTest, DoesNotDependOnTheThreadCount) {
  const OccupancyGrid grid = test::RoomGrid(70, 60, 0.1, 0.05, 8);
  const RayCastScene scene(grid, GetParam());
  const RayBatch batch = test::FanBatch(grid, 21, 13, 5.0, 9);
  const int threads = omp_get_max_threads();
  std::vector<RayHit> hits_one, hits_two;
  KernelRecord one, two;
  omp_set_num_threads(1);
  CastRayBatchRecorded(scene, batch, hits_one, one);
  omp_set_num_threads(3);
  CastRayBatchRecorded(scene, batch, hits_two, two);
  omp_set_num_threads(threads);
  EXPECT_EQ(one.fetch_offsets, two.fetch_offsets);
  EXPECT_EQ(one.fetch_addresses, two.fetch_addresses);
  EXPECT_EQ(one.node_exits, two.node_exits);
  EXPECT_EQ(one.last_exits, two.last_exits);
}

// A launch whose queries are filled on demand, segment by segment, is
// recorded as the batch of those queries, on every SIMD path (the lanes cast
// adjacent unkept blocks in place and gather the rest; scalar code casts
// segment by segment), sampled or not, at any thread count; each query is
// filled once.
TEST_P(RecordTest, AFilledLaunchIsRecordedAsTheBatchOfItsQueries) {
  const OccupancyGrid grid = test::RoomGrid(70, 60, 0.1, 0.05, 8);
  const RayCastScene scene(grid, GetParam());
  const RayBatch batch = test::FanBatch(grid, 120, 37, 5.0, 9);
  const int threads = omp_get_max_threads();
  for (SimdLevel level : test::SimdLevelsThisCpuRuns())
    for (int sampled_sms : {0, 1, 2})
      for (int thread_count : {1, 2}) {
        SCOPED_TRACE(std::string(ToString(level)) + ", sampled_sms " + std::to_string(sampled_sms) + ", " +
                     std::to_string(thread_count) + " thread(s)");
        const test::ScopedSimdLimit limit(level);
        omp_set_num_threads(thread_count);
        RecordOptions options;
        options.sample.sampled_sms = sampled_sms;
        options.sample.block_stride = 2;
        std::vector<RayHit> want_hits;
        KernelRecord want, got;
        CastRayBatchRecorded(scene, batch, want_hits, want, options);
        std::atomic<std::size_t> filled{0};
        std::atomic<bool> outside{false};
        const QueryFiller fill = [&](std::size_t begin, std::size_t end, RayQuery* out) {
          if (begin > end || end > batch.queries.size()) {
            outside = true;
            return;
          }
          std::copy(batch.queries.begin() + static_cast<long>(begin), batch.queries.begin() + static_cast<long>(end),
                    out);
          filled += end - begin;
        };
        std::vector<RayHit> hits(batch.queries.size(), RayHit{-1.0f, 7});
        CastRayBatchRecordedFilled(scene, batch.queries.size(), batch.max_range_m, fill, hits, got, options);
        omp_set_num_threads(threads);
        ASSERT_FALSE(outside.load());
        EXPECT_EQ(filled.load(), batch.queries.size());
        ASSERT_NO_THROW(got.Validate());
        EXPECT_EQ(got.fetch_offsets, want.fetch_offsets);
        EXPECT_EQ(got.address_offsets, want.address_offsets);
        EXPECT_EQ(got.fetch_addresses, want.fetch_addresses);
        EXPECT_EQ(got.last_exits, want.last_exits);
        EXPECT_EQ(got.touched_sectors, want.touched_sectors);
        for (std::size_t i = 0; i < hits.size(); ++i) {
          ASSERT_EQ(hits[i].range_m, want_hits[i].range_m) << i;
          ASSERT_EQ(hits[i].nodes, want_hits[i].nodes) << i;
        }
      }
  std::vector<RayHit> short_hits(10);
  KernelRecord record;
  const QueryFiller none = [](std::size_t, std::size_t, RayQuery*) {};
  EXPECT_THROW(CastRayBatchRecordedFilled(scene, 11, 5.0, none, short_hits, record), std::invalid_argument);
}

// A sampled record keeps exactly the addresses of the queries on the
// sampled SMs (of their blocks, every block_stride-th), equal to the full
// record's, and everything else in full.
class SampleTest : public ::testing::TestWithParam<std::tuple<RayCastMethod, int>> {};

TEST_P(SampleTest, KeepsTheSampledBlocksAddressesOnly) {
  const auto [method, block_stride] = GetParam();
  const OccupancyGrid grid = test::RoomGrid(70, 60, 0.1, 0.05, 8);
  const RayCastScene scene(grid, method);
  const RayBatch batch = test::FanBatch(grid, 120, 37, 5.0, 9);  // 4440 queries: 17+ blocks of 256
  std::vector<RayHit> hits_full, hits_sampled;
  KernelRecord full, sampled;
  CastRayBatchRecorded(scene, batch, hits_full, full);
  RecordOptions options;
  options.sample.sampled_sms = 2;  // SMs 0 and 4 of 8
  options.sample.block_stride = block_stride;
  CastRayBatchRecorded(scene, batch, hits_sampled, sampled, options);
  ASSERT_NO_THROW(sampled.Validate());
  ASSERT_TRUE(sampled.sampled());
  EXPECT_EQ(sampled.fetch_offsets, full.fetch_offsets);
  EXPECT_EQ(sampled.last_exits, full.last_exits);
  std::size_t kept = 0;
  for (std::size_t q = 0; q < full.query_count(); ++q) {
    ASSERT_EQ(hits_sampled[q].range_m, hits_full[q].range_m) << q;
    const std::size_t block = q / 32 / 8;
    const bool keeps = (block % 8 == 0 || block % 8 == 4) && (block / 8) % block_stride == 0;
    ASSERT_EQ(sampled.KeepsAddresses(q), keeps) << q;
    if (!keeps) continue;
    ++kept;
    for (std::uint32_t k = 0; k < full.nodes(q); ++k) ASSERT_EQ(sampled.addresses(q)[k], full.addresses(q)[k]);
  }
  EXPECT_GT(kept, 0u);
  EXPECT_LT(kept, full.query_count() / 3);
  // The sectors the whole batch touched, counted while casting (in SIMD
  // lanes where the CPU has them), are the full record's distinct sectors.
  std::set<std::uint64_t> distinct;
  for (std::uint64_t a : full.fetch_addresses) distinct.insert((a - full.footprint_begin()) / 32);
  EXPECT_EQ(sampled.touched_sectors, distinct.size());
}

INSTANTIATE_TEST_SUITE_P(AllRayCasters, RecordTest,
                         ::testing::Values(RayCastMethod::kMarch, RayCastMethod::kDda, RayCastMethod::kRayMarching),
                         [](const auto& info) { return ToString(info.param); });
INSTANTIATE_TEST_SUITE_P(EveryBlockAndEverySecond, SampleTest,
                         ::testing::Combine(::testing::Values(RayCastMethod::kMarch, RayCastMethod::kDda,
                                                              RayCastMethod::kRayMarching),
                                            ::testing::Values(1, 2)),
                         [](const auto& info) {
                           return ToString(std::get<0>(info.param)) + "_stride" +
                                  std::to_string(std::get<1>(info.param));
                         });

TEST(KernelRecord, AddressIsBasePlusIndexTimesElementSize) {
  OccupancyGrid grid(20, 10, 0.5);  // all free: the ray runs to the border
  for (RayCastMethod m : {RayCastMethod::kDda, RayCastMethod::kRayMarching}) {
    const RayCastScene scene(grid, m);
    RayBatch batch;
    batch.max_range_m = 100;
    batch.queries.push_back({5.25, 2.25, 0.0});  // cell (10, 4), heading +x
    std::vector<RayHit> hits;
    KernelRecord record;
    CastRayBatchRecorded(scene, batch, hits, record);
    const MemoryRegion& r = record.regions[0];
    EXPECT_EQ(record.fetch_addresses[0], r.base + grid.Index(10, 4) * r.element_bytes);
    EXPECT_EQ(record.ExitAt(0, record.nodes(0) - 1), kRayEndReturn);  // left the map
    if (m == RayCastMethod::kRayMarching) {
      // The distance field is placed after the grid: distinct bases.
      EXPECT_GE(r.base, DeviceLayout{}.first_base + grid.cell_count());
    } else {
      EXPECT_EQ(r.base, DeviceLayout{}.first_base);
      EXPECT_EQ(record.nodes(0), 10u);  // cells 10..19
    }
  }
}

TEST(KernelRecord, ValidateCatchesInconsistentRecords) {
  const auto program = ShippedStepProgram(StepProgramKind::kDdaStep);
  KernelRecordBuilder builder(program, StepProgramKind::kDdaStep, test::ByteRegion(4096, 64));
  builder.AddQuery({4096, 4097}, {kNoExit, 1});
  KernelRecord ok = builder.Build();
  KernelRecord bad_exit = ok;
  bad_exit.node_exits[1] = 2;  // the dda loop has RETURN_IF #0 and #1 only
  EXPECT_THROW(bad_exit.Validate(), std::logic_error);
  KernelRecord bad_address = ok;
  bad_address.fetch_addresses[0] = 4096 + 64;
  EXPECT_THROW(bad_address.Validate(), std::logic_error);
  KernelRecord bad_offsets = ok;
  bad_offsets.fetch_offsets.back() = 1;
  EXPECT_THROW(bad_offsets.Validate(), std::logic_error);
  // Two regions with a gap: addresses in either are valid, one in the gap
  // (between the lowest and highest valid ones) is not.
  KernelRecord two_regions = ok;
  two_regions.regions.push_back(test::ByteRegion(8192, 64));
  two_regions.fetch_addresses[1] = 8192 + 63;
  EXPECT_NO_THROW(two_regions.Validate());
  two_regions.fetch_addresses[0] = 6000;
  EXPECT_THROW(two_regions.Validate(), std::logic_error);
}

// Tallied exits (CollideBatchRecorded's form): a profile per query whose
// passes add up to its node count, naming only the loop's RETURN_IFs, and
// no per-fetch exit beside it; ExitAt has no pass to name and refuses.
TEST(KernelRecord, ValidateChecksTalliedExits) {
  const auto program = ShippedStepProgram(StepProgramKind::kDdaStep);
  KernelRecordBuilder builder(program, StepProgramKind::kDdaStep, test::ByteRegion(4096, 64));
  builder.AddQuery({4096, 4097, 4098}, {kNoExit, 1, kNoExit});
  builder.AddQuery({}, {});
  const KernelRecord with_node_exits = builder.Build();
  auto tallied = [&](ExitProfile profile) {
    KernelRecord r = with_node_exits;
    r.node_exits.clear();
    r.tallied_exits = std::make_shared<const ExitProfile>(std::move(profile));
    return r;
  };
  const ExitProfile good{{0, 2, 2}, {0, 2}, {2, 1}};  // two quiet passes, one at RETURN_IF #1; none
  EXPECT_NO_THROW(tallied(good).Validate());
  EXPECT_THROW(tallied(good).ExitAt(0, 0), std::logic_error);
  ExitProfile short_passes = good;
  short_passes.passes[0] = 1;
  EXPECT_THROW(tallied(short_passes).Validate(), std::logic_error);
  ExitProfile unknown_exit = good;
  unknown_exit.variant[1] = 3;  // RETURN_IF #2: the dda loop has #0 and #1 only
  EXPECT_THROW(tallied(unknown_exit).Validate(), std::logic_error);
  ExitProfile past_the_end{{0, 5, 2}, {0, 2}, {2, 1}};  // an offset beyond the lists, though the last is right
  EXPECT_THROW(tallied(past_the_end).Validate(), std::logic_error);
  ExitProfile one_query_short{{0, 2}, {0, 2}, {2, 1}};
  EXPECT_THROW(tallied(one_query_short).Validate(), std::logic_error);
  KernelRecord both = tallied(good);
  both.node_exits = with_node_exits.node_exits;
  EXPECT_THROW(both.Validate(), std::logic_error);
}

TEST(RoboCoreApi, ExecuteRecordsTheConfiguredProgramAndChecksTheDecode) {
  const OccupancyGrid grid = test::RoomGrid(40, 40, 0.1, 0.05, 3);
  const RayCastScene scene(grid, RayCastMethod::kMarch);
  const RayBatch batch = test::FanBatch(grid, 4, 8, 3.0, 4);
  RoboCoreContext robocore;
  robocore.ConfigRoboCore(ShippedStepProgram(StepProgramKind::kGridMarch), nullptr);
  robocore.ConfigDecode({{FetchKind::kGridCell, 1}});
  std::vector<RayHit> hits, reference;
  KernelRecord record;
  robocore.ExecuteRoboCore(batch, scene, hits, record);
  CastRayBatch(scene, batch, reference);
  for (std::size_t i = 0; i < hits.size(); ++i) EXPECT_EQ(hits[i].range_m, reference[i].range_m);
  EXPECT_EQ(record.leaf, nullptr);
  EXPECT_EQ(record.program->name(), "grid_march");

  robocore.ConfigDecode({{FetchKind::kGridCell, 8}});  // the artifact's doubles
  EXPECT_THROW(robocore.ExecuteRoboCore(batch, scene, hits, record), std::invalid_argument);
  robocore.ConfigDecode({{FetchKind::kDistanceCell, 4}});
  EXPECT_THROW(robocore.ExecuteRoboCore(batch, scene, hits, record), std::invalid_argument);
  // A ray program needs the hit and end exits (RETURN_IF #0 and #1).
  EXPECT_THROW(robocore.ConfigRoboCore(test::Program("loop:\n LOAD a, b\n RETURN_IF a\n")), std::invalid_argument);
}

}  // namespace
}  // namespace rc
