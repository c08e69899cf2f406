#include "workloads/delibot/trace_simulator.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "robocore/ray_cast.h"
#include "simulator/room_map.h"
#include "workloads/delibot/sensor_model.h"

namespace rc {
namespace {

using test::ClearanceToBlocking;
using test::MakeRoomWithDoor;

// Motion from a to b in a's frame (written here, not taken from the
// simulator, so that a shared bug cannot hide).
Pose2 RelativeMotion(const Pose2& a, const Pose2& b) {
  const double c = std::cos(a.theta), s = std::sin(a.theta);
  const double dx = b.x - a.x, dy = b.y - a.y;
  return {c * dx + s * dy, -s * dx + c * dy, WrapAngle(b.theta - a.theta)};
}

double MotionDifference(const Pose2& a, const Pose2& b) {
  return std::max({std::abs(a.x - b.x), std::abs(a.y - b.y), std::abs(WrapAngle(a.theta - b.theta))});
}

// The exact dda range of every beam at a ground-truth pose.
std::vector<float> DdaRanges(const OccupancyGrid& grid, const Pose2& truth, const LaserGeometry& g) {
  const Pose2 sensor = SensorPose(truth, g);
  NoFetchVisitor none;
  std::vector<float> out;
  for (int i = 0; i < g.beam_count; ++i)
    out.push_back(CastDda(grid, sensor.x, sensor.y, sensor.theta + g.BeamAngle(i), g.max_range_m, none).range_m);
  return out;
}

SimulationOptions Quiet(int records) {
  SimulationOptions options;
  options.DisableNoise();
  options.record_count = records;
  return options;
}

TEST(TraceSimulator, GroundTruthStaysInFreeSpaceWithTheRobotDiscClear) {
  const OccupancyGrid grid = MakeRoomWithDoor();
  SimulationOptions options;  // every noise source on, people included
  options.record_count = 500;
  options.kidnap_record = 250;
  const SimulatedTrace sim = SimulateTrace(grid, options);
  ASSERT_EQ(sim.trace.scans.size(), 500u);
  ASSERT_EQ(sim.ground_truth.size(), 500u);
  EXPECT_EQ(sim.trace.format, "cmu");
  EXPECT_GE(sim.planning_radius_m, options.robot_radius_m);
  for (std::size_t k = 0; k < sim.ground_truth.size(); ++k) {
    const Pose2& p = sim.ground_truth[k].pose;
    ASSERT_TRUE(grid.IsFreePoint(p.x, p.y)) << "record " << k;
    ASSERT_GE(ClearanceToBlocking(grid, p.x, p.y, 1.0), sim.planning_radius_m - 1e-9) << "record " << k;
    const Pose2 sensor = SensorPose(p, options.geometry);
    ASSERT_TRUE(grid.IsFreePoint(sensor.x, sensor.y)) << "record " << k;
    EXPECT_DOUBLE_EQ(sim.ground_truth[k].time_s, k / options.laser_rate_hz);
    EXPECT_EQ(sim.trace.scans[k].time_s, sim.ground_truth[k].time_s);
    ASSERT_EQ(sim.trace.scans[k].ranges_m.size(), 180u);
    for (float r : sim.trace.scans[k].ranges_m) {
      ASSERT_GE(r, 0.0f);
      ASSERT_LE(r, static_cast<float>(options.geometry.max_range_m));
    }
  }
}

TEST(TraceSimulator, NoiseFreeRangesEqualDdaFromTheGroundTruthSensorPose) {
  const OccupancyGrid grid = MakeRoomWithDoor();
  const SimulatedTrace sim = SimulateTrace(grid, Quiet(200));
  double travelled_m = 0.0;
  for (std::size_t k = 0; k < sim.ground_truth.size(); ++k) {
    const std::vector<float> expected = DdaRanges(grid, sim.ground_truth[k].pose, sim.trace.geometry);
    ASSERT_EQ(sim.trace.scans[k].ranges_m, expected) << "record " << k;
    if (k > 0)
      travelled_m += std::hypot(sim.ground_truth[k].pose.x - sim.ground_truth[k - 1].pose.x,
                                sim.ground_truth[k].pose.y - sim.ground_truth[k - 1].pose.y);
  }
  EXPECT_GT(travelled_m, 3.0) << "the robot should have driven somewhere";
}

TEST(TraceSimulator, MotionRespectsSpeedAndTurnRate) {
  const OccupancyGrid grid = MakeRoomWithDoor();
  SimulationOptions options = Quiet(400);
  options.speed_mps = 0.8;
  options.turn_rate_radps = 0.5;
  const SimulatedTrace sim = SimulateTrace(grid, options);
  const double dt = 1.0 / options.laser_rate_hz;
  double fastest = 0.0, fastest_turn = 0.0;
  for (std::size_t k = 1; k < sim.ground_truth.size(); ++k) {
    const Pose2 m = RelativeMotion(sim.ground_truth[k - 1].pose, sim.ground_truth[k].pose);
    const double distance = std::hypot(m.x, m.y);
    EXPECT_LE(distance, options.speed_mps * dt + 1e-9) << "record " << k;
    EXPECT_LE(std::abs(m.theta), options.turn_rate_radps * dt + 1e-9) << "record " << k;
    fastest = std::max(fastest, distance);
    fastest_turn = std::max(fastest_turn, std::abs(m.theta));
  }
  EXPECT_NEAR(fastest, options.speed_mps * dt, 1e-9);
  EXPECT_NEAR(fastest_turn, options.turn_rate_radps * dt, 1e-9);
}

TEST(TraceSimulator, OdometryWithoutDriftReproducesTheTrueIncrements) {
  const OccupancyGrid grid = MakeRoomWithDoor();
  SimulationOptions options;  // range noise and people on: they must not matter
  options.record_count = 300;
  options.odometry_translation_sigma = 0.0;
  options.odometry_rotation_sigma = 0.0;
  options.odometry_translation_bias = 0.0;
  options.odometry_heading_drift_rad_per_m = 0.0;
  const SimulatedTrace sim = SimulateTrace(grid, options);
  // The odometry frame is not the map frame.
  const Pose2 expected_start = [&] {
    const Pose2& t = sim.ground_truth[0].pose;
    const Pose2& f = kDefaultOdometryFrame;
    return Pose2{f.x + std::cos(f.theta) * t.x - std::sin(f.theta) * t.y,
                 f.y + std::sin(f.theta) * t.x + std::cos(f.theta) * t.y, WrapAngle(f.theta + t.theta)};
  }();
  EXPECT_LT(MotionDifference(sim.trace.scans[0].odometry, expected_start), 1e-12);
  EXPECT_GT(std::hypot(sim.trace.scans[0].odometry.x - sim.ground_truth[0].pose.x,
                       sim.trace.scans[0].odometry.y - sim.ground_truth[0].pose.y),
            5.0);
  for (std::size_t k = 1; k < sim.ground_truth.size(); ++k) {
    const Pose2 odo = RelativeMotion(sim.trace.scans[k - 1].odometry, sim.trace.scans[k].odometry);
    const Pose2 tru = RelativeMotion(sim.ground_truth[k - 1].pose, sim.ground_truth[k].pose);
    ASSERT_LT(MotionDifference(odo, tru), 1e-9) << "record " << k;
  }
}

// Map each odometry pose into the map frame through the start poses; with
// perfect odometry this gives the ground truth back.
double OdometryPositionError(const SimulatedTrace& sim, std::size_t k) {
  const Pose2 rel = RelativeMotion(sim.trace.scans[0].odometry, sim.trace.scans[k].odometry);
  const Pose2& start = sim.ground_truth[0].pose;
  const double c = std::cos(start.theta), s = std::sin(start.theta);
  const double x = start.x + c * rel.x - s * rel.y, y = start.y + s * rel.x + c * rel.y;
  return std::hypot(x - sim.ground_truth[k].pose.x, y - sim.ground_truth[k].pose.y);
}

// The largest of those errors over records [first, last). A maximum, not the
// last value: a heading error displaces poses in proportion to their
// distance from the start, so a route that ends near its start hides it.
double MaxOdometryPositionError(const SimulatedTrace& sim, std::size_t first, std::size_t last) {
  double worst = 0.0;
  for (std::size_t k = first; k < last; ++k) worst = std::max(worst, OdometryPositionError(sim, k));
  return worst;
}

TEST(TraceSimulator, HeadingDriftAddsItsRatePerMetreDriven) {
  const OccupancyGrid grid = MakeRoomWithDoor();
  SimulationOptions options = Quiet(600);
  options.odometry_heading_drift_rad_per_m = 0.02;
  const SimulatedTrace sim = SimulateTrace(grid, options);
  double driven_m = 0.0, heading_error = 0.0;
  for (std::size_t k = 1; k < sim.ground_truth.size(); ++k) {
    const Pose2 odo = RelativeMotion(sim.trace.scans[k - 1].odometry, sim.trace.scans[k].odometry);
    const Pose2 tru = RelativeMotion(sim.ground_truth[k - 1].pose, sim.ground_truth[k].pose);
    const double step_m = std::hypot(tru.x, tru.y);
    ASSERT_NEAR(WrapAngle(odo.theta - tru.theta), 0.02 * step_m, 1e-9) << "record " << k;
    ASSERT_NEAR(std::hypot(odo.x, odo.y), step_m, 1e-9) << "record " << k;
    driven_m += step_m;
    heading_error += WrapAngle(odo.theta - tru.theta);
  }
  EXPECT_GT(driven_m, 15.0);
  EXPECT_NEAR(heading_error, 0.02 * driven_m, 1e-6);
  EXPECT_GT(MaxOdometryPositionError(sim, 0, 600), 0.5);
}

TEST(TraceSimulator, OdometryWithDefaultNoiseDivergesFromTheTruth) {
  const OccupancyGrid grid = MakeRoomWithDoor();
  SimulationOptions options;  // default noise, bias and drift
  options.record_count = 600;
  const SimulatedTrace sim = SimulateTrace(grid, options);
  int differing_increments = 0;
  for (std::size_t k = 1; k < sim.ground_truth.size(); ++k) {
    const Pose2 odo = RelativeMotion(sim.trace.scans[k - 1].odometry, sim.trace.scans[k].odometry);
    const Pose2 tru = RelativeMotion(sim.ground_truth[k - 1].pose, sim.ground_truth[k].pose);
    if (MotionDifference(odo, tru) > 1e-6) ++differing_increments;
  }
  EXPECT_GT(differing_increments, 400);
  const double early = MaxOdometryPositionError(sim, 0, 100);
  const double late = MaxOdometryPositionError(sim, 300, 600);
  EXPECT_GT(late, 0.2);
  EXPECT_GT(late, 1.5 * early);
}

TEST(TraceSimulator, KidnapTeleportsExactlyOnceAtTheGivenRecord) {
  const OccupancyGrid grid = MakeRoomWithDoor();
  SimulationOptions options = Quiet(250);
  options.kidnap_record = 120;
  const SimulatedTrace sim = SimulateTrace(grid, options);
  ASSERT_EQ(sim.trace.scans.size(), 250u);
  EXPECT_EQ(sim.kidnap_record, 120);
  int mismatches = 0;
  for (std::size_t k = 1; k < sim.ground_truth.size(); ++k) {
    const Pose2 odo = RelativeMotion(sim.trace.scans[k - 1].odometry, sim.trace.scans[k].odometry);
    const Pose2 tru = RelativeMotion(sim.ground_truth[k - 1].pose, sim.ground_truth[k].pose);
    if (MotionDifference(odo, tru) > 1e-6) {
      ++mismatches;
      EXPECT_EQ(k, 120u);
    }
  }
  EXPECT_EQ(mismatches, 1);
  const Pose2& before = sim.ground_truth[119].pose;
  const Pose2& after = sim.ground_truth[120].pose;
  EXPECT_GE(std::hypot(after.x - before.x, after.y - before.y), 1.0);
  // The robot drives on from its new pose.
  const Pose2& last = sim.ground_truth.back().pose;
  EXPECT_GT(std::hypot(last.x - after.x, last.y - after.y), 0.5);

  SimulationOptions no_kidnap = Quiet(250);
  EXPECT_EQ(SimulateTrace(grid, no_kidnap).kidnap_record, -1);
}

void ExpectIdentical(const SimulatedTrace& a, const SimulatedTrace& b) {
  ASSERT_EQ(a.trace.scans.size(), b.trace.scans.size());
  EXPECT_EQ(a.kidnap_record, b.kidnap_record);
  for (std::size_t k = 0; k < a.trace.scans.size(); ++k) {
    ASSERT_EQ(a.trace.scans[k].ranges_m, b.trace.scans[k].ranges_m) << "record " << k;
    ASSERT_EQ(a.trace.scans[k].odometry.x, b.trace.scans[k].odometry.x);
    ASSERT_EQ(a.trace.scans[k].odometry.y, b.trace.scans[k].odometry.y);
    ASSERT_EQ(a.trace.scans[k].odometry.theta, b.trace.scans[k].odometry.theta);
    ASSERT_EQ(a.ground_truth[k].pose.x, b.ground_truth[k].pose.x);
    ASSERT_EQ(a.ground_truth[k].pose.y, b.ground_truth[k].pose.y);
    ASSERT_EQ(a.ground_truth[k].pose.theta, b.ground_truth[k].pose.theta);
  }
}

TEST(TraceSimulator, SameOptionsAndSeedGiveTheSameTrace) {
  const OccupancyGrid grid = MakeRoomWithDoor();
  SimulationOptions options;  // all noise, people, and a kidnap
  options.record_count = 300;
  options.people_count = 3;
  options.kidnap_record = 100;
  ExpectIdentical(SimulateTrace(grid, options), SimulateTrace(grid, options));
  SimulationOptions other = options;
  other.seed = 2;
  const SimulatedTrace a = SimulateTrace(grid, options), b = SimulateTrace(grid, other);
  EXPECT_NE(a.trace.scans[0].ranges_m, b.trace.scans[0].ranges_m);
}

TEST(TraceSimulator, ExplicitOdometryStartIsUsed) {
  const OccupancyGrid grid = MakeRoomWithDoor();
  SimulationOptions options = Quiet(5);
  options.odometry_start = Pose2{100.0, -200.0, -1.0};
  const SimulatedTrace sim = SimulateTrace(grid, options);
  EXPECT_EQ(sim.trace.scans[0].odometry.x, 100.0);
  EXPECT_EQ(sim.trace.scans[0].odometry.y, -200.0);
  EXPECT_EQ(sim.trace.scans[0].odometry.theta, -1.0);
}

// Per-beam statistics of readings against the exact ranges.
struct BeamComparison {
  long returns = 0;  // beams whose exact range is a real return
  long at_max = 0;   // ... read as max range
  long shorter = 0;  // ... read shorter than exact by > 1 mm
  long longer = 0;   // ... read longer than exact by > 1 mm
  long shorter_with_shorter_neighbour = 0;
  double sum_error = 0.0, sum_squared_error = 0.0;
  double sum_short_fraction = 0.0;
};

BeamComparison Compare(const OccupancyGrid& grid, const SimulatedTrace& sim) {
  BeamComparison c;
  const double max = sim.trace.geometry.max_range_m;
  for (std::size_t k = 0; k < sim.trace.scans.size(); ++k) {
    const std::vector<float> exact = DdaRanges(grid, sim.ground_truth[k].pose, sim.trace.geometry);
    const std::vector<float>& read = sim.trace.scans[k].ranges_m;
    for (std::size_t i = 0; i < exact.size(); ++i) {
      if (exact[i] >= max) continue;
      ++c.returns;
      const double error = static_cast<double>(read[i]) - exact[i];
      c.sum_error += error;
      c.sum_squared_error += error * error;
      if (read[i] >= max) ++c.at_max;
      if (error < -1e-3) {
        ++c.shorter;
        c.sum_short_fraction += read[i] / exact[i];
        const bool left = i > 0 && read[i - 1] < exact[i - 1] - 1e-3;
        const bool right = i + 1 < exact.size() && read[i + 1] < exact[i + 1] - 1e-3;
        if (left || right) ++c.shorter_with_shorter_neighbour;
      }
      if (error > 1e-3) ++c.longer;
    }
  }
  return c;
}

TEST(TraceSimulator, DropoutsReadMaxRangeAtTheirProbability) {
  const OccupancyGrid grid = MakeRoomWithDoor();
  SimulationOptions options = Quiet(100);
  options.max_range_dropout_probability = 0.2;
  const BeamComparison c = Compare(grid, SimulateTrace(grid, options));
  ASSERT_GT(c.returns, 10000);
  EXPECT_NEAR(static_cast<double>(c.at_max) / c.returns, 0.2, 0.015);
  EXPECT_EQ(c.shorter, 0);
}

TEST(TraceSimulator, ShortReadingsAreUniformBelowTheTrueRange) {
  const OccupancyGrid grid = MakeRoomWithDoor();
  SimulationOptions options = Quiet(100);
  options.short_reading_probability = 0.1;
  const BeamComparison c = Compare(grid, SimulateTrace(grid, options));
  EXPECT_EQ(c.longer, 0);
  EXPECT_NEAR(static_cast<double>(c.shorter) / c.returns, 0.1, 0.01);
  EXPECT_NEAR(c.sum_short_fraction / c.shorter, 0.5, 0.03);
  // Independent per beam: a short beam rarely has a short neighbour.
  EXPECT_LT(static_cast<double>(c.shorter_with_shorter_neighbour) / c.shorter, 0.3);
}

TEST(TraceSimulator, GaussianRangeNoiseHasTheGivenSigma) {
  const OccupancyGrid grid = MakeRoomWithDoor();
  SimulationOptions options = Quiet(100);
  options.range_sigma_m = 0.05;
  const BeamComparison c = Compare(grid, SimulateTrace(grid, options));
  const double mean = c.sum_error / c.returns;
  EXPECT_NEAR(mean, 0.0, 0.002);
  EXPECT_NEAR(std::sqrt(c.sum_squared_error / c.returns - mean * mean), 0.05, 0.002);
}

TEST(TraceSimulator, PeopleCastCoherentShortReadings) {
  const OccupancyGrid grid = MakeRoomWithDoor();
  SimulationOptions options = Quiet(300);
  options.people_count = 4;
  const BeamComparison c = Compare(grid, SimulateTrace(grid, options));
  EXPECT_EQ(c.longer, 0);
  EXPECT_GT(c.shorter, 200);
  // A person blocks a fan of adjacent beams, not isolated ones.
  EXPECT_GT(static_cast<double>(c.shorter_with_shorter_neighbour) / c.shorter, 0.8);
}

TEST(TraceSimulator, StopsAtTheRouteEndWhenAsked) {
  const OccupancyGrid grid = MakeRoomWithDoor();
  SimulationOptions options = Quiet(100000);
  options.waypoint_count = 3;
  options.stop_at_route_end = true;
  const SimulatedTrace sim = SimulateTrace(grid, options);
  ASSERT_LT(sim.trace.scans.size(), 100000u);
  const Pose2& end = sim.ground_truth.back().pose;
  EXPECT_EQ(end.x, sim.route.waypoints.back().x_m);
  EXPECT_EQ(end.y, sim.route.waypoints.back().y_m);
  // Without the flag the robot keeps going for all N records.
  options.stop_at_route_end = false;
  options.record_count = static_cast<int>(sim.trace.scans.size()) + 200;
  const SimulatedTrace longer = SimulateTrace(grid, options);
  EXPECT_EQ(longer.trace.scans.size(), static_cast<std::size_t>(options.record_count));
  const Pose2& later = longer.ground_truth.back().pose;
  EXPECT_GT(std::hypot(later.x - end.x, later.y - end.y), 0.0);
}

std::string SimulationError(const OccupancyGrid& grid, const SimulationOptions& options) {
  try {
    SimulateTrace(grid, options);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no error";
}

TEST(TraceSimulator, MapErrorsAreReported) {
  const SimulationOptions options = Quiet(10);
  const OccupancyGrid walls(50, 50, 0.05, CellState::kOccupied);
  EXPECT_NE(SimulationError(walls, options).find("no free cell"), std::string::npos);
  const OccupancyGrid corridor(200, 8, 0.05, CellState::kFree);  // 0.4 m wide
  EXPECT_NE(SimulationError(corridor, options).find("too narrow"), std::string::npos);
}

TEST(TraceSimulator, InvalidOptionsAreRejected) {
  const OccupancyGrid grid = MakeRoomWithDoor();
  SimulationOptions options = Quiet(10);
  options.kidnap_record = 10;  // must be below record_count
  std::string error;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("kidnap_record"), std::string::npos);
  EXPECT_THROW(SimulateTrace(grid, options), std::invalid_argument);
  options = Quiet(10);
  options.range_sigma_m = -0.1;
  EXPECT_THROW(SimulateTrace(grid, options), std::invalid_argument);
  options = Quiet(10);
  options.short_reading_probability = std::nan("");
  EXPECT_FALSE(options.IsValid(nullptr));
  options = Quiet(10);
  options.laser_rate_hz = 0.0;
  EXPECT_FALSE(options.IsValid(nullptr));
}

}  // namespace
}  // namespace rc
