#pragma once
// A small asymmetric test world and an exact (noise-free or lightly noisy)
// trace through it, built directly from the dda ray caster so that MCL tests
// do not depend on the trace simulator.
#include <stdexcept>
#include <vector>

#include "common/random_stream.h"
#include "maps/occupancy_grid.h"
#include "robocore/ray_cast.h"
#include "traces/sensor_trace.h"
#include "workloads/delibot/sensor_model.h"

namespace rc::test {

// 12 m x 8 m at 0.1 m: outer walls, an L-shaped inner wall, two pillars and
// a box, placed so that no two places look alike.
inline OccupancyGrid AsymmetricRoom() {
  OccupancyGrid g(120, 80, 0.1);
  auto wall = [&](int x0, int y0, int x1, int y1) {
    for (int x = x0; x <= x1; ++x)
      for (int y = y0; y <= y1; ++y) g.Set(x, y, CellState::kOccupied);
  };
  wall(0, 0, 119, 1);
  wall(0, 78, 119, 79);
  wall(0, 0, 1, 79);
  wall(118, 0, 119, 79);
  wall(40, 2, 41, 45);                                             // inner wall from the bottom
  wall(41, 44, 70, 45);                                            // its horizontal arm
  wall(85, 20, 88, 23);                                            // pillar
  wall(20, 60, 22, 62);                                            // pillar
  wall(95, 55, 110, 70);                                           // box
  for (int y = 30; y < 40; ++y) g.Set(0, y, CellState::kUnknown);  // a patch of unknown
  return g;
}

struct SyntheticRun {
  SensorTrace trace;
  std::vector<Pose2> truth;
};

// Drives through waypoints (straight segments) and records a scan every
// step_m metres; odometry equals truth in a rotated, shifted frame.
inline SyntheticRun DriveThrough(const OccupancyGrid& g, const std::vector<Pose2>& waypoints, double step_m,
                                 double range_noise_m, std::uint64_t seed) {
  SyntheticRun run;
  run.trace.format = "synthetic";
  run.trace.geometry.max_range_m = 20.0;
  const RayCastScene scene(g, RayCastMethod::kDda);
  const Pose2 odom_origin{3.0, -2.0, 0.7};  // odometry frame != map frame
  long k = 0;
  for (std::size_t w = 0; w + 1 < waypoints.size(); ++w) {
    const Pose2 a = waypoints[w], b = waypoints[w + 1];
    const double len = std::hypot(b.x - a.x, b.y - a.y);
    const double heading = std::atan2(b.y - a.y, b.x - a.x);
    const int steps = std::max(1, static_cast<int>(len / step_m));
    for (int s = 0; s < steps; ++s, ++k) {
      Pose2 p{a.x + (b.x - a.x) * s / steps, a.y + (b.y - a.y) * s / steps, heading};
      if (!g.IsFreePoint(p.x, p.y) ||
          !g.IsFreePoint(SensorPose(p, run.trace.geometry).x, SensorPose(p, run.trace.geometry).y))
        throw std::logic_error("synthetic route passes through an obstacle");
      LaserScan scan;
      scan.time_s = 0.1 * k;
      const double c = std::cos(odom_origin.theta), sn = std::sin(odom_origin.theta);
      scan.odometry = {odom_origin.x + c * p.x - sn * p.y, odom_origin.y + sn * p.x + c * p.y,
                       WrapAngle(p.theta + odom_origin.theta)};
      const Pose2 sensor = SensorPose(p, run.trace.geometry);
      RandomStream noise(seed, StreamPurpose::kTest, k, 0);
      for (int i = 0; i < run.trace.geometry.beam_count; ++i) {
        double z = CastRay(scene, sensor.x, sensor.y, sensor.theta + run.trace.geometry.BeamAngle(i),
                           run.trace.geometry.max_range_m)
                       .range_m;
        if (range_noise_m > 0) z = std::clamp(z + noise.Gaussian(range_noise_m), 0.0, run.trace.geometry.max_range_m);
        scan.ranges_m.push_back(static_cast<float>(z));
      }
      run.trace.scans.push_back(scan);
      run.truth.push_back(p);
    }
  }
  return run;
}

inline std::vector<Pose2> RoomTour() {
  return {{1.0, 1.0, 0}, {3.0, 2.0, 0}, {3.0, 6.5, 0}, {8.0, 6.5, 0}, {10.5, 4.0, 0}, {10.5, 1.0, 0}, {5.0, 1.0, 0}};
}

}  // namespace rc::test
