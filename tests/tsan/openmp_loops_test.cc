// Every OpenMP loop of the suite's libraries, run with four threads on small
// inputs: the ThreadSanitizer stage of CI (run_tsan.sh) runs this binary
// and the SACT property test, whose own loop is in the test. A loop that no
// test runs under TSan is unchecked, so docs/robustness.md lists which test
// here reaches which loop (checked with llvm-cov on this binary).
#include <omp.h>

#include <gtest/gtest.h>

#include "delibot/synthetic_world.h"
#include "robocore/address_sample.h"
#include "robocore/ray_batch.h"
#include "robocore/ray_cast.h"
#include "workloads/delibot/delibot_run.h"

namespace rc {
namespace {

DelibotSettings SmallRun(SensorModelKind model) {
  DelibotSettings s;
  s.sensor_model = model;
  s.mcl.particle_count = 300;
  s.mcl.beams.beam_step = 10;
  s.mcl.seed = 7;
  s.max_records = 6;
  return s;
}

// monte_carlo_localizer.cc (motion update), beam_sensor_model.cc (both
// loops), ray_batch_recorded.cc (the recorded casts), and the pricing of
// every update: backend.cc (PriceAll), pricing_context.cc (the replays'
// tasks), memory_replay.cc (two loops and the sampled estimate's tasks),
// rt_warp_cycles.cc and rt_unit_model.cc. The replay is sampled as the
// CLI's defaults sample it (one SM, every second block), so that the
// estimate's tasks run; every priced cost must not depend on the threads.
TEST(OpenMpLoops, BeamModelFilterWithPricingAndHypotheses) {
  omp_set_num_threads(4);
  const OccupancyGrid g = test::AsymmetricRoom();
  const test::SyntheticRun run = test::DriveThrough(g, test::RoomTour(), 0.2, 0.03, 5);
  DelibotSettings s = SmallRun(SensorModelKind::kBeam);
  s.price_backends = true;
  s.ledger.replay_sms = kReplaySms;
  s.ledger.replay_block_stride = kReplayBlockStride;
  s.mcl.hypothesis_floor.min_particles = 60;
  s.mcl.max_particle_count = 900;
  const DelibotResult threaded = RunDelibot(g, run.trace, &run.truth, s);
  omp_set_num_threads(1);
  const DelibotResult serial = RunDelibot(g, run.trace, &run.truth, s);
  ASSERT_EQ(threaded.rows.size(), serial.rows.size());
  int priced = 0;
  for (std::size_t i = 0; i < serial.rows.size(); ++i) {
    EXPECT_EQ(threaded.rows[i].estimate.x, serial.rows[i].estimate.x) << i;
    EXPECT_EQ(threaded.rows[i].nodes, serial.rows[i].nodes) << i;
    const LedgerIteration& a = threaded.rows[i].pricing;
    const LedgerIteration& b = serial.rows[i].pricing;
    ASSERT_EQ(a.costs.size(), b.costs.size()) << i;
    for (std::size_t k = 0; k < a.costs.size(); ++k) {
      EXPECT_EQ(a.costs[k].cycles, b.costs[k].cycles) << i << " backend " << k;
      EXPECT_EQ(a.costs[k].memory.l2_accesses, b.costs[k].memory.l2_accesses) << i << " backend " << k;
    }
    priced += a.priced;
  }
  EXPECT_TRUE(threaded.priced);
  EXPECT_GT(priced, 0);
}

// likelihood_field_model.cc.
TEST(OpenMpLoops, LikelihoodFieldFilter) {
  omp_set_num_threads(4);
  const OccupancyGrid g = test::AsymmetricRoom();
  const test::SyntheticRun run = test::DriveThrough(g, test::RoomTour(), 0.2, 0.03, 5);
  const DelibotResult r = RunDelibot(g, run.trace, &run.truth, SmallRun(SensorModelKind::kLikelihoodField));
  EXPECT_EQ(r.rows.size(), 6u);
}

// ray_batch.cc.
TEST(OpenMpLoops, RayBatch) {
  omp_set_num_threads(4);
  const OccupancyGrid g = test::AsymmetricRoom();
  const RayCastScene scene(g, RayCastMethod::kDda);
  RayBatch batch;
  batch.max_range_m = 5.0;
  for (int i = 0; i < 2000; ++i) batch.queries.push_back({1.0 + 0.001 * i, 1.5, 0.003 * i});
  std::vector<RayHit> hits;
  CastRayBatch(scene, batch, hits);
  ASSERT_EQ(hits.size(), batch.queries.size());
  for (std::size_t i = 0; i < hits.size(); i += 97) {
    const RayQuery& q = batch.queries[i];
    const RayHit one = CastRay(scene, q.origin_x_m, q.origin_y_m, q.angle_rad, batch.max_range_m);
    EXPECT_EQ(hits[i].range_m, one.range_m) << i;
  }
}

}  // namespace
}  // namespace rc
