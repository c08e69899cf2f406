// End-to-end localization on a synthetic world (a reduced version of the
// accuracy study, small enough for CI): global localization, tracking,
// kidnapping, and scans made entirely of outliers.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "support/sanitizer_build.h"
#include "synthetic_world.h"
#include "workloads/delibot/delibot_run.h"
#include "workloads/delibot/monte_carlo_localizer.h"

namespace rc {
namespace {

DelibotSettings Settings(int particles, std::uint64_t seed) {
  DelibotSettings s;
  s.mcl.particle_count = particles;
  s.mcl.beams.beam_step = 6;
  s.mcl.seed = seed;
  s.beam.max_range_m = 12.0;
  s.ray_caster = RayCastMethod::kRayMarching;  // = dda's ranges, fewer fetches
  return s;
}

TEST(MclLocalizationTest, GlobalLocalizationConvergesOnEverySeed) {
  const OccupancyGrid g = test::AsymmetricRoom();
  const test::SyntheticRun run = test::DriveThrough(g, test::RoomTour(), 0.15, 0.03, 11);
  const std::uint64_t seeds = test::FullOrUnderSanitizer(3, 1);
  for (std::uint64_t seed = 1; seed <= seeds; ++seed) {
    for (auto model : {SensorModelKind::kBeam, SensorModelKind::kLikelihoodField}) {
      DelibotSettings s = Settings(4000, seed);
      s.sensor_model = model;
      const DelibotResult r = RunDelibot(g, run.trace, &run.truth, s);
      EXPECT_TRUE(r.summary.converged) << "seed " << seed << " " << ToString(model);
      EXPECT_GE(r.summary.convergence_iteration, 0);
      EXPECT_LT(r.summary.final_err_xy_m, 0.2) << "seed " << seed << " " << ToString(model);
      EXPECT_LT(r.summary.final_err_theta_rad, 5.0 * kPi / 180) << "seed " << seed;
      EXPECT_FALSE(r.summary.any_non_finite_weight);
    }
  }
}

TEST(MclLocalizationTest, TrackingFromAKnownStartKeepsMedianErrorBelowTenCentimetres) {
  const OccupancyGrid g = test::AsymmetricRoom();
  const test::SyntheticRun run = test::DriveThrough(g, test::RoomTour(), 0.1, 0.03, 12);
  for (auto caster : {RayCastMethod::kMarch, RayCastMethod::kDda, RayCastMethod::kRayMarching}) {
    DelibotSettings s = Settings(500, 3);
    s.ray_caster = caster;
    s.initial_pose = run.truth.front();
    const DelibotResult r = RunDelibot(g, run.trace, &run.truth, s);
    EXPECT_EQ(r.summary.convergence_iteration, 0) << ToString(caster);
    EXPECT_LT(r.summary.median_err_xy_m, 0.1) << ToString(caster);
  }
}

// A tour of the room, then the robot is carried elsewhere and drives on; its
// odometry continues smoothly from where it was, so only the scans reveal
// the kidnap. Returns the trace and the index of the first kidnapped record.
std::pair<test::SyntheticRun, std::size_t> KidnappedRun() {
  const OccupancyGrid g = test::AsymmetricRoom();
  test::SyntheticRun run = test::DriveThrough(g, test::RoomTour(), 0.15, 0.03, 13);
  const test::SyntheticRun second = test::DriveThrough(
      g, {{6.0, 3.0, 0}, {6.0, 1.0, 0}, {11.0, 1.0, 0}, {11.0, 4.0, 0}, {8.0, 4.0, 0}, {8.0, 7.5, 0}}, 0.15, 0.03, 14);
  const std::size_t kidnap_at = run.trace.scans.size();
  const Pose2 last_odom = run.trace.scans.back().odometry;
  const Pose2 first_odom = second.trace.scans.front().odometry;
  for (std::size_t i = 0; i < second.trace.scans.size(); ++i) {
    LaserScan scan = second.trace.scans[i];
    // Re-anchor the second run's odometry on the first run's last pose.
    const double dth = last_odom.theta - first_odom.theta;
    const double dx = scan.odometry.x - first_odom.x, dy = scan.odometry.y - first_odom.y;
    scan.odometry = {last_odom.x + std::cos(dth) * dx - std::sin(dth) * dy,
                     last_odom.y + std::sin(dth) * dx + std::cos(dth) * dy, WrapAngle(scan.odometry.theta + dth)};
    run.trace.scans.push_back(scan);
    run.truth.push_back(second.truth[i]);
  }
  return {run, kidnap_at};
}

TEST(MclLocalizationTest, RecoversFromAKidnap) {
  const OccupancyGrid g = test::AsymmetricRoom();
  const auto [run, kidnap_at] = KidnappedRun();
  // A sanitizer build runs plain augmented MCL only; the injection check's
  // code runs there in InjectionCheckRefusesPosesThatFitOnlyTheOccludedScans.
  const std::vector<int> checks = test::FullOrUnderSanitizer(std::vector<int>{0, 10}, std::vector<int>{0});
  for (int check : checks) {
    DelibotSettings s = Settings(3000, 21);
    s.initial_pose = run.truth.front();
    s.mcl.injection_check_updates = check;
    const DelibotResult r = RunDelibot(g, run.trace, &run.truth, s);
    EXPECT_LT(r.rows[kidnap_at - 1].err_xy_m, 0.2) << "tracked before the kidnap; check " << check;
    EXPECT_GT(r.rows[kidnap_at + 1].err_xy_m, 1.0) << "the kidnap displaced the robot; check " << check;
    EXPECT_GT(r.summary.injected, 0) << "augmented MCL must inject particles; check " << check;
    EXPECT_LT(r.rows.back().err_xy_m, 0.2) << "recovered after the kidnap; check " << check;
  }
}

TEST(MclLocalizationTest, InjectionCheckRefusesPosesThatFitOnlyTheOccludedScans) {
  const OccupancyGrid g = test::AsymmetricRoom();
  test::SyntheticRun run = test::DriveThrough(g, test::RoomTour(), 0.15, 0.03, 16);
  // A person steps in front of the laser for eight scans: the middle third
  // of the beams reads 15 cm. The true pose explains those scans badly for
  // a moment, augmented MCL starts drawing random poses, and without a
  // check one that faces a nearby wall can outscore the whole true cloud.
  for (std::size_t i = 40; i < 48; ++i)
    for (std::size_t b = 60; b < 120; ++b) run.trace.scans[i].ranges_m[b] = 0.15f;
  DelibotSettings s = Settings(500, 5);
  s.initial_pose = run.truth.front();
  s.mcl.injection_check_updates = 10;
  const DelibotResult r = RunDelibot(g, run.trace, &run.truth, s);
  EXPECT_GT(r.summary.injection_rejected, 0) << "the occlusion must make augmented MCL draw random poses";
  for (const DelibotRow& row : r.rows) EXPECT_LT(row.err_xy_m, 0.3) << "record " << row.iteration;
  EXPECT_EQ(r.summary.convergence_iteration, 0);
}

TEST(MclLocalizationTest, ScansOfOnlyOutliersKeepEveryWeightFinite) {
  const OccupancyGrid g = test::AsymmetricRoom();
  test::SyntheticRun run = test::DriveThrough(g, test::RoomTour(), 0.15, 0.03, 15);
  // Twenty consecutive scans in which every beam hit something unmodelled
  // 5 cm from the sensor: every particle's likelihood is tiny.
  for (std::size_t i = 30; i < 50; ++i)
    for (float& z : run.trace.scans[i].ranges_m) z = 0.05f;
  DelibotSettings s = Settings(1000, 4);
  s.initial_pose = run.truth.front();
  s.mcl.beams.beam_step = 1;  // all 180 beams
  const DelibotResult r = RunDelibot(g, run.trace, &run.truth, s);
  EXPECT_FALSE(r.summary.any_non_finite_weight);
  for (const auto& row : r.rows) {
    ASSERT_TRUE(std::isfinite(row.ess)) << row.iteration;
    ASSERT_GE(row.ess, 1.0 - 1e-9) << row.iteration;
  }
  EXPECT_LT(r.rows.back().err_xy_m, 0.2);
}

TEST(MclLocalizationTest, MapWithNoFreeCellIsRefused) {
  const OccupancyGrid g(20, 20, 0.1, CellState::kOccupied);
  test::SyntheticRun run;
  run.trace.scans.resize(1);
  run.trace.scans[0].ranges_m.assign(180, 1.0f);
  EXPECT_THROW(RunDelibot(g, run.trace, nullptr, Settings(100, 1)), std::invalid_argument);
}

}  // namespace
}  // namespace rc
