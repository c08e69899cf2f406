// The MRPT reference engine: it localizes on a synthetic world (so the
// settings mapping is not broken), is deterministic for a seed, runs MRPT's
// own example log, and is reported through our writers.
#include <cmath>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "common/input_error.h"
#include "delibot/synthetic_world.h"
#include "maps/mrpt/mrpt_map_dispatch.h"
#include "mrpt/mrpt_test_data.h"
#include "support/temp_dir.h"
#include "traces/mrpt/mrpt_rawlog_reader.h"
#include "workloads/delibot/mrpt/delibot_engine.h"

namespace rc {
namespace {

DelibotSettings TrackingSettings(SensorModelKind model, const Pose2& start) {
  DelibotSettings s;
  s.sensor_model = model;
  s.mcl.particle_count = 300;
  s.mcl.beams.beam_step = 6;
  s.mcl.alpha_slow = s.mcl.alpha_fast = 0.0;  // MRPT has no recovery; compare like with like
  s.beam.max_range_m = 20.0;
  s.initial_pose = start;
  return s;
}

class MrptEngineTracking : public ::testing::TestWithParam<SensorModelKind> {};

TEST_P(MrptEngineTracking, FollowsTheSyntheticTourLikeOurs) {
  const OccupancyGrid g = test::AsymmetricRoom();
  const test::SyntheticRun run = test::DriveThrough(g, test::RoomTour(), 0.2, 0.03, 7);
  const DelibotSettings s = TrackingSettings(GetParam(), run.truth.front());
  for (DelibotEngine engine : {DelibotEngine::kOurs, DelibotEngine::kMrpt}) {
    SCOPED_TRACE(ToString(engine));
    const DelibotResult r = RunDelibotEngine(engine, g, run.trace, &run.truth, s);
    ASSERT_EQ(r.rows.size(), run.trace.scans.size());
    EXPECT_EQ(r.work_counted, engine == DelibotEngine::kOurs);
    EXPECT_FALSE(r.summary.any_non_finite_weight);
    EXPECT_EQ(r.summary.convergence_iteration, 0);  // started at the truth
    EXPECT_LT(r.summary.median_err_xy_m, 0.15);
    EXPECT_LT(r.summary.p95_err_xy_m, 0.35);
    EXPECT_LT(r.summary.final_err_xy_m, 0.3);
    EXPECT_GT(r.summary.sensor_updates, static_cast<long>(run.trace.scans.size() / 2));
  }
}

INSTANTIATE_TEST_SUITE_P(BothModels, MrptEngineTracking,
                         ::testing::Values(SensorModelKind::kBeam, SensorModelKind::kLikelihoodField),
                         [](const auto& info) { return ToString(info.param); });

TEST(MrptEngine, SameSeedSameRunOtherSeedOtherRun) {
  const OccupancyGrid g = test::AsymmetricRoom();
  const test::SyntheticRun run = test::DriveThrough(g, test::RoomTour(), 0.4, 0.03, 7);
  DelibotSettings s = TrackingSettings(SensorModelKind::kLikelihoodField, run.truth.front());
  const DelibotResult a = RunDelibotEngine(DelibotEngine::kMrpt, g, run.trace, &run.truth, s);
  const DelibotResult b = RunDelibotEngine(DelibotEngine::kMrpt, g, run.trace, &run.truth, s);
  s.mcl.seed = 2;
  const DelibotResult c = RunDelibotEngine(DelibotEngine::kMrpt, g, run.trace, &run.truth, s);
  bool differs = false;
  for (std::size_t k = 0; k < a.rows.size(); ++k) {
    EXPECT_EQ(a.rows[k].estimate.x, b.rows[k].estimate.x);
    EXPECT_EQ(a.rows[k].estimate.y, b.rows[k].estimate.y);
    EXPECT_EQ(a.rows[k].estimate.theta, b.rows[k].estimate.theta);
    differs |= a.rows[k].estimate.x != c.rows[k].estimate.x;
  }
  EXPECT_TRUE(differs);
}

TEST(MrptEngine, RefusesOptionsOnlyOurFilterHas) {
  const OccupancyGrid g = test::AsymmetricRoom();
  const test::SyntheticRun run = test::DriveThrough(g, test::RoomTour(), 0.4, 0.03, 7);
  const DelibotSettings plain = TrackingSettings(SensorModelKind::kLikelihoodField, run.truth.front());
  std::vector<DelibotSettings> ours(4, plain);
  ours[0].mcl.initial_particle_count = 3000;
  ours[1].mcl.hypothesis_floor.min_particles = 100;
  ours[2].mcl.hypothesis_floor.min_particles = 100;
  ours[2].mcl.max_particle_count = 3000;
  ours[3].mcl.injection_check_updates = 10;
  for (std::size_t k = 0; k < ours.size(); ++k) {
    // A UsageError: the command line exits with 2 (common/exit_codes.h).
    EXPECT_THROW(RunDelibotEngine(DelibotEngine::kMrpt, g, run.trace, &run.truth, ours[k]), UsageError)
        << "settings " << k;
    // Our engine runs them.
    DelibotSettings short_run = ours[k];
    short_run.max_records = 5;
    EXPECT_NO_THROW(RunDelibotEngine(DelibotEngine::kOurs, g, run.trace, &run.truth, short_run)) << "settings " << k;
  }
}

TEST(MrptEngine, TimelineHasOurColumnsWithKernelWorkEmpty) {
  const OccupancyGrid g = test::AsymmetricRoom();
  const test::SyntheticRun run = test::DriveThrough(g, test::RoomTour(), 0.6, 0.03, 7);
  const DelibotSettings s = TrackingSettings(SensorModelKind::kLikelihoodField, run.truth.front());
  const DelibotResult r = RunDelibotEngine(DelibotEngine::kMrpt, g, run.trace, &run.truth, s);
  const std::string path = test::ProgramTempPath("timeline.csv");
  WriteDelibotTimeline(path, r);
  std::ifstream in(path);
  std::string header, first;
  std::getline(in, header);
  std::getline(in, first);
  EXPECT_EQ(header.rfind("iteration,time_s,est_x_m,est_y_m,est_theta_rad,ess,rays,nodes,nodes_per_ray,wall_s,", 0), 0u)
      << header;
  EXPECT_NE(header.find("err_xy_m"), std::string::npos);
  EXPECT_EQ(header.find("cycles_"), std::string::npos);  // no modelled cost for MRPT
  // Fields 7-9 (rays, nodes, nodes_per_ray) are empty.
  std::vector<std::string> fields;
  std::stringstream line(first);
  for (std::string f; std::getline(line, f, ',');) fields.push_back(f);
  ASSERT_GT(fields.size(), 9u);
  EXPECT_EQ(fields[6], "");
  EXPECT_EQ(fields[7], "");
  EXPECT_EQ(fields[8], "");
  EXPECT_NE(fields[2], "");
  const nlohmann::json json = DelibotEngineSummaryJson(DelibotEngine::kMrpt, r, s, DelibotProvenance{});
  EXPECT_EQ(json["engine"], "mrpt");
  EXPECT_EQ(json["config"]["mrpt"]["resamplingMethod"], "prSystematic");
  EXPECT_TRUE(json["totals"]["rays"].is_null());
  std::filesystem::remove(path);
}

TEST(MrptEngine, RunsMrptsLocalizationDemoThroughBothEngines) {
  RC_REQUIRE_MRPT_DATASET("localization_demo.rawlog");
  RC_REQUIRE_MRPT_DATASET("localization_demo.simplemap.gz");
  const LoadedMapWithOrigin map = LoadMapWithMrpt(test::MrptDatasetPath("localization_demo.simplemap.gz"));
  const SensorTrace trace = ReadMrptRawlog(test::MrptDatasetPath("localization_demo.rawlog"));
  DelibotSettings s;
  s.sensor_model = SensorModelKind::kLikelihoodField;
  s.mcl.particle_count = 400;
  s.mcl.beams.beam_step = 12;
  s.beam.max_range_m = trace.geometry.max_range_m;
  for (DelibotEngine engine : {DelibotEngine::kOurs, DelibotEngine::kMrpt}) {
    SCOPED_TRACE(ToString(engine));
    const DelibotResult r = RunDelibotEngine(engine, map.map.grid, trace, nullptr, s);
    ASSERT_EQ(r.rows.size(), trace.scans.size());
    EXPECT_FALSE(r.summary.any_non_finite_weight);
    EXPECT_GT(r.summary.sensor_updates, 10);
    for (const DelibotRow& row : r.rows) {
      EXPECT_TRUE(std::isfinite(row.estimate.x) && std::isfinite(row.estimate.y));
      EXPECT_TRUE(map.map.grid.Contains(static_cast<int>(row.estimate.x / map.map.grid.resolution_m()),
                                        static_cast<int>(row.estimate.y / map.map.grid.resolution_m())));
    }
  }
}

}  // namespace
}  // namespace rc
