// The batch kernels in SIMD lanes (ray_batch_lanes.h), in every instruction
// set this CPU runs (AVX2, AVX-512), against the per-query kernels: every
// hit's range (bit for bit) and node count must be equal, for every batch
// size (lane refill), on random, open and real maps, on the geometry
// degeneracies of ray_cast_test.cc, and at any thread count. An instruction
// set the CPU lacks is not checked here (the test log says which ran); on a
// CPU with neither, CastRayBatch takes the per-query path, which the batch
// tests still check.
#include <omp.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "common/angles.h"
#include "common/cpu_features.h"
#include "common/random_stream.h"
#include "maps/cmu_map_loader.h"
#include "maps/office_map_generator.h"
#include "robocore/ray_batch.h"
#include "robocore/ray_batch_lanes.h"
#include "support/random_grid.h"
#include "support/simd_levels.h"
#include "support/test_data.h"

namespace rc {
namespace {

using test::RandomGrid;

// Origins anywhere in (and a little outside) the map, free or not, with
// headings that include the axis directions exactly.
RayBatch MixedBatch(const OccupancyGrid& g, int n, double max_range, std::uint64_t seed) {
  RayBatch batch;
  batch.max_range_m = max_range;
  RandomStream s(seed, StreamPurpose::kTest, 2, 0);
  const double axis_angles[] = {0.0, kPi / 2, kPi, -kPi / 2, kPi / 4, -3 * kPi / 4};
  for (int i = 0; i < n; ++i) {
    const double margin = 2 * g.resolution_m();
    double x = s.Uniform(-margin, g.extent_x_m() + margin), y = s.Uniform(-margin, g.extent_y_m() + margin);
    if (i % 5 == 0) {  // on cell corners and grid lines
      x = std::floor(x / g.resolution_m()) * g.resolution_m();
      if (i % 10 == 0) y = std::floor(y / g.resolution_m()) * g.resolution_m();
    }
    const double a = i % 3 == 0 ? axis_angles[s.Below(6)] : s.Uniform(-kPi, kPi);
    batch.queries.push_back({x, y, a});
  }
  return batch;
}

// Free-cell origins, as a filter casts them.
RayBatch FreeBatch(const OccupancyGrid& g, int n, double max_range, std::uint64_t seed) {
  RayBatch batch;
  batch.max_range_m = max_range;
  const std::vector<std::uint32_t> free_cells = g.FreeCellIndices();
  RandomStream s(seed, StreamPurpose::kTest, 3, 0);
  const double r = g.resolution_m();
  for (int i = 0; i < n && !free_cells.empty(); ++i) {
    const std::uint32_t c = free_cells[s.Below(free_cells.size())];
    const int ix = static_cast<int>(c / g.size_y()), iy = static_cast<int>(c % g.size_y());
    batch.queries.push_back({(ix + s.Uniform()) * r, (iy + s.Uniform()) * r, s.Uniform(-kPi, kPi)});
  }
  return batch;
}

void ExpectHitsEqualSingleQueries(const RayCastScene& scene, const RayBatch& batch, const std::vector<RayHit>& hits,
                                  const char* what) {
  ASSERT_EQ(hits.size(), batch.queries.size());
  for (std::size_t i = 0; i < hits.size(); ++i) {
    const RayQuery& q = batch.queries[i];
    const RayHit single = CastRay(scene, q.origin_x_m, q.origin_y_m, q.angle_rad, batch.max_range_m);
    // Bit for bit, not merely ==: -0.0f and 0.0f would compare equal.
    ASSERT_EQ(std::memcmp(&hits[i].range_m, &single.range_m, sizeof(float)), 0)
        << what << " " << ToString(scene.method()) << " query " << i << " (" << q.origin_x_m << ", " << q.origin_y_m
        << ", " << q.angle_rad << "): " << hits[i].range_m << " vs " << single.range_m;
    ASSERT_EQ(hits[i].nodes, single.nodes) << what << " " << ToString(scene.method()) << " query " << i;
  }
}

// Every entry point: CastRayBatch (whichever path this CPU takes) and the
// lanes in each instruction set the CPU runs.
void ExpectBatchEqualsSingleQueries(const RayCastScene& scene, const RayBatch& batch, const char* what) {
  std::vector<RayHit> hits;
  CastRayBatch(scene, batch, hits);
  ExpectHitsEqualSingleQueries(scene, batch, hits, what);
  if (!RayLanesApply(scene)) return;
  for (RayLaneIsa isa : HostRayLaneIsas()) {
    SCOPED_TRACE(std::string(ToString(isa)));
    std::vector<RayHit> lane_hits(batch.queries.size());
    CastRayLanesIn(isa, scene, batch.queries.data(), batch.queries.size(), batch.max_range_m, lane_hits.data());
    ExpectHitsEqualSingleQueries(scene, batch, lane_hits, what);
  }
}

TEST(RayBatchLanesTest, TheCpuFeaturesChooseTheInstructionSets) {
  std::vector<RayLaneIsa> expected;
  if (CpuHasAvx2()) expected.push_back(RayLaneIsa::kAvx2);
  if (CpuHasAvx512()) expected.push_back(RayLaneIsa::kAvx512);
  EXPECT_EQ(HostRayLaneIsas(), expected);
  EXPECT_EQ(RayLanesSupported(), !expected.empty());
  const OccupancyGrid g(10, 10, 0.1);
  for (RayCastMethod m : {RayCastMethod::kDda, RayCastMethod::kRayMarching, RayCastMethod::kMarch})
    EXPECT_EQ(RayLanesApply(RayCastScene(g, m)), !expected.empty());
  std::string ran;
  for (RayLaneIsa isa : expected) ran += " " + std::string(ToString(isa));
  std::printf("lanes checked on this CPU:%s\n", ran.empty() ? " none (per-query path only)" : ran.c_str());
}

TEST(RayBatchLanesTest, RefusesAnInstructionSetTheCpuLacks) {
  const OccupancyGrid g(10, 10, 0.1);
  const RayCastScene scene(g, RayCastMethod::kDda);
  const RayQuery q{0.5, 0.5, 0.3};
  RayHit hit;
  for (RayLaneIsa isa : {RayLaneIsa::kAvx2, RayLaneIsa::kAvx512}) {
    const bool runs = (isa == RayLaneIsa::kAvx2 ? CpuHasAvx2() : CpuHasAvx512());
    if (runs)
      EXPECT_NO_THROW(CastRayLanesIn(isa, scene, &q, 1, 5.0, &hit));
    else
      EXPECT_THROW(CastRayLanesIn(isa, scene, &q, 1, 5.0, &hit), std::invalid_argument);
  }
}

constexpr RayCastMethod kMethods[] = {RayCastMethod::kMarch, RayCastMethod::kDda, RayCastMethod::kRayMarching};

// A lowered SIMD level (rcbench --simd) picks the lanes CastRayBatch runs,
// or none (one query at a time), and every level gives the same hits.
TEST(RayBatchLanesTest, TheSimdLevelInUsePicksTheLanes) {
  const OccupancyGrid g = test::RandomGrid(90, 70, 0.1, 0.05, 4);
  const RayBatch batch = FreeBatch(g, 3000, 8.0, 9);
  for (RayCastMethod m : kMethods) {
    const RayCastScene scene(g, m);
    std::vector<RayHit> widest;
    CastRayBatch(scene, batch, widest);
    for (SimdLevel level : test::SimdLevelsThisCpuRuns()) {
      const test::ScopedSimdLimit limit(level);
      EXPECT_EQ(RayLanesApply(scene), level != SimdLevel::kScalar);
      if (level != SimdLevel::kScalar) {
        EXPECT_EQ(RayLaneIsaInUse(), level == SimdLevel::kAvx512 ? RayLaneIsa::kAvx512 : RayLaneIsa::kAvx2);
      }
      std::vector<RayHit> hits;
      CastRayBatch(scene, batch, hits);
      ASSERT_EQ(hits.size(), widest.size());
      for (std::size_t i = 0; i < hits.size(); ++i) {
        ASSERT_EQ(std::memcmp(&hits[i].range_m, &widest[i].range_m, sizeof(float)), 0)
            << ToString(level) << " " << ToString(m) << " query " << i;
        ASSERT_EQ(hits[i].nodes, widest[i].nodes) << ToString(level) << " " << ToString(m) << " query " << i;
      }
    }
  }
}

TEST(RayBatchLanesTest, EqualsSingleQueriesOnRandomMaps) {
  for (std::uint64_t seed = 1; seed <= 3; ++seed)
    for (double density : {0.002, 0.05, 0.3}) {
      const OccupancyGrid g = RandomGrid(150, 110, 0.05, density, seed);
      for (RayCastMethod m : kMethods) {
        const RayCastScene scene(g, m);
        ExpectBatchEqualsSingleQueries(scene, MixedBatch(g, 6000, 4.0, seed), "mixed");
        ExpectBatchEqualsSingleQueries(scene, FreeBatch(g, 6000, 12.0, seed), "free");
      }
    }
}

TEST(RayBatchLanesTest, EqualsSingleQueriesOnExactBinaryResolution) {
  // 0.25 m cells: origins on grid lines and corners are exact, so ties and
  // rays along grid lines really happen.
  const OccupancyGrid g = RandomGrid(40, 40, 0.25, 0.06, 5);
  for (RayCastMethod m : kMethods)
    ExpectBatchEqualsSingleQueries(RayCastScene(g, m), MixedBatch(g, 20000, 10.0, 5), "binary");
}

TEST(RayBatchLanesTest, EqualsSingleQueriesForEveryBatchSize) {
  const OccupancyGrid g = GenerateOfficeMap(OfficeMapOptions{});
  for (RayCastMethod m : kMethods) {
    const RayCastScene scene(g, m);
    // Up to several refills of every lane in flight.
    const RayBatch all = FreeBatch(g, 3 * kRaysInFlight + 1, 10.0, 7);
    for (std::size_t n = 0; n <= all.queries.size(); ++n) {
      RayBatch part = all;
      part.queries.resize(n);
      ExpectBatchEqualsSingleQueries(scene, part, "prefix");
    }
  }
}

TEST(RayBatchLanesTest, WallsAndMapsWithoutFreeCells) {
  for (CellState fill : {CellState::kOccupied, CellState::kUnknown}) {
    const OccupancyGrid g(6, 6, 0.5, fill);
    for (RayCastMethod m : kMethods)
      ExpectBatchEqualsSingleQueries(RayCastScene(g, m), MixedBatch(g, 200, 10.0, 11), "walls");
  }
}

TEST(RayBatchLanesTest, EqualsSingleQueriesOnWean) {
  RC_REQUIRE_SHARED_DATA("wean/wean.dat");
  const OccupancyGrid g = LoadCmuMap(test::SharedDataPath("wean/wean.dat"));
  for (RayCastMethod m : kMethods)
    ExpectBatchEqualsSingleQueries(RayCastScene(g, m), FreeBatch(g, 50000, 10.0, 13), "wean");
}

TEST(RayBatchLanesTest, SameHitsAtAnyThreadCount) {
  const OccupancyGrid g = GenerateOfficeMap(OfficeMapOptions{});
  for (RayCastMethod m : kMethods) {
    const RayCastScene scene(g, m);
    const RayBatch batch = FreeBatch(g, 20000, 10.0, 17);
    const int saved = omp_get_max_threads();
    std::vector<RayHit> one, two;
    omp_set_num_threads(1);
    CastRayBatch(scene, batch, one);
    omp_set_num_threads(2);
    CastRayBatch(scene, batch, two);
    omp_set_num_threads(saved);
    ASSERT_EQ(one.size(), two.size());
    for (std::size_t i = 0; i < one.size(); ++i) {
      ASSERT_EQ(std::memcmp(&one[i].range_m, &two[i].range_m, sizeof(float)), 0) << i;
      ASSERT_EQ(one[i].nodes, two[i].nodes) << i;
    }
  }
}

}  // namespace
}  // namespace rc
