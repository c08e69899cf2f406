// The threshold policy's threshold is the crossover of the backends' cost models:
// a linear scan over nodes per query, pricing the same probe batches by
// hand, must find the same n as the bisection.
#include <cmath>

#include <gtest/gtest.h>

#include "backends/backend.h"
#include "backends/scheduler/backend_ledger.h"
#include "backends/scheduler/crossover_threshold.h"
#include "maps/occupancy_grid.h"
#include "robocore/ray_batch_recorded.h"

namespace rc {
namespace {

KernelRecord LayoutRecord(const OccupancyGrid& grid, RayCastMethod method) {
  const RayCastScene scene(grid, method);
  RayBatch one;
  one.max_range_m = 5.0;
  one.queries.push_back({1.05, 1.05, 0.3});
  std::vector<RayHit> hits;
  KernelRecord record;
  CastRayBatchRecorded(scene, one, hits, record);
  return record;
}

double Advantage(const Backend& high, const Backend& low, const KernelRecord& t, std::size_t q, std::uint32_t n) {
  const KernelRecord probe = MakeUniformProbe(t, q, n);
  return static_cast<double>(low.Price(probe).cycles) - static_cast<double>(high.Price(probe).cycles);
}

TEST(CrossoverTest, BisectionFindsTheCrossoverALinearScanFinds) {
  const OccupancyGrid grid(200, 200, 0.05);
  const KernelRecord layout = LayoutRecord(grid, RayCastMethod::kDda);
  // The default models give no single crossover on dda (with the FP64
  // kernel, RoboCore is slightly cheaper at one node per ray and SIMT at
  // longer rays; docs/simt_instruction_counts.md). Price the FP32 kernel,
  // make SIMT's loads expensive (one L1 sector per cycle) and give the RT
  // unit more OP units and L1 ports, so that a single crossover exists, as
  // the paper's DeliBot has: SIMT wins short rays (the RT unit's program
  // configuration overhead), RoboCore long ones.
  BackendParameters params;
  params.simt.precision = SimtPrecision::kFp32;
  params.simt.l1_sectors_per_cycle = 1;
  params.robocore.unit.intersection_unit_sets = 8;
  params.robocore.unit.sector_requests_per_cycle = 4;
  const auto high = Backend::Create("robocore", params);
  const auto low = Backend::Create("simt", params);
  const std::size_t queries = 4096;
  const CrossoverResult found = DeriveCrossoverThreshold(*high, *low, layout, queries, 256);
  ASSERT_TRUE(found.has_crossing);
  std::uint32_t scanned = 0;
  for (std::uint32_t n = 1; n <= 256; ++n) {
    if (Advantage(*high, *low, layout, queries, n) > 0.0) {
      scanned = n - 1;
      break;
    }
  }
  EXPECT_EQ(found.threshold_nodes_per_query, static_cast<double>(scanned));
  EXPECT_LE(Advantage(*high, *low, layout, queries, scanned), 0.0);
  EXPECT_GT(Advantage(*high, *low, layout, queries, scanned + 1), 0.0);
}

TEST(CrossoverTest, WithoutACrossingTheThresholdPolicyStaysOnTheCheaperBackend) {
  const OccupancyGrid grid(200, 200, 0.05);
  const KernelRecord layout = LayoutRecord(grid, RayCastMethod::kDda);
  // The FP32 SIMT kernel is cheaper than RoboCore at every length here (the
  // FP64 kernel's two prologue divisions make RoboCore 2% cheaper at one
  // node per ray, so the defaults have no clean "no crossing" case).
  BackendParameters params;
  params.simt.precision = SimtPrecision::kFp32;
  const auto high = Backend::Create("robocore", params);
  const auto low = Backend::Create("simt", params);
  const CrossoverResult found = DeriveCrossoverThreshold(*high, *low, layout, 4096, 256);
  EXPECT_FALSE(found.has_crossing);
  EXPECT_TRUE(std::isinf(found.threshold_nodes_per_query));
  LedgerOptions options;
  options.policy.kind = SchedulerKind::kThreshold;
  BackendLedger ledger(params, options);
  ledger.Prepare(layout, 4096);
  for (double npr : {-1.0, 5.0, 500.0}) EXPECT_EQ(ledger.BeginIteration(), "simt") << npr;
}

}  // namespace
}  // namespace rc
