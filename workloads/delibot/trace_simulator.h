#pragma once
// Synthetic laser traces with ground truth, for `rcbench simulate`: a disc
// robot drives a seeded collision-free route (free_space_route.h) through any
// occupancy grid, and a laser scans the map with dda ray casting (exact
// ranges) plus a configurable noise model.
//
// Modelled:
//   - motion: straight segments at a constant speed, turns in place at a
//     constant rate, no acceleration limits;
//   - range noise: Gaussian, on real returns only (a no-return stays one);
//   - short readings from unmodelled obstacles, independent per beam
//     (reading uniform in [0, true range]), plus optional moving "people"
//     discs that are ray-cast against, so their short readings are
//     spatially coherent like real clutter;
//   - max-range dropouts (reading = max range = no return);
//   - odometry: the true motion increment between records with
//     multiplicative noise on translation and rotation, a translation scale
//     bias, and a heading drift proportional to the distance driven;
//   - an optional kidnap: the true robot teleports, the odometry does not
//     see it.
// Not modelled: the laser's own angular resolution and beam width (each
// beam is an ideal ray), range quantisation (a file writer does it: the CMU
// format stores whole centimetres), reflectance and mixed pixels, motion
// during a sweep (a scan is instantaneous), and interaction between the
// robot and people: people walk their own seeded collision-free routes
// through the robot's reachable space, passing through the robot and each
// other (a person whose disc contains the laser is not seen by that scan).
//
// Determinism: every draw comes from RandomStream(seed, kSimulation, step,
// index), with step = record, waypoint or goal number and index naming the
// noise source (see trace_simulator.cc), so the same options give the same
// trace on any platform and thread count.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/angles.h"
#include "maps/occupancy_grid.h"
#include "traces/ground_truth_io.h"
#include "traces/sensor_trace.h"
#include "workloads/delibot/free_space_route.h"

namespace rc {

// The default odometry frame: odometry pose = kDefaultOdometryFrame composed
// with the true pose (the map frame moved by this fixed transform, m, m,
// rad), far enough away that using odometry as map coordinates is an
// obvious error. With odometry noise off, every odometry pose is then this
// transform of the true pose.
inline constexpr Pose2 kDefaultOdometryFrame{13.0, -7.0, 0.7};
// Clearance (m) the route keeps between the laser and the walls when the
// laser sits outside the robot's disc (offset >= radius), so that it can
// never scan from inside a wall.
inline constexpr double kLaserWallClearanceM = 0.05;

struct SimulationOptions {
  std::uint64_t seed = 1;  // all draws: route, noise, people, kidnap

  // Sensor: beam layout, max range (m) and the laser's forward offset (m).
  // Default: LaserGeometry's, the CMU Wean Hall SICK (180 beams over 180
  // deg, 81.83 m, 0.25 m ahead of the robot centre).
  LaserGeometry geometry;

  // Robot and route.
  double robot_radius_m = 0.2;   // disc robot, (0, 10] m. The route keeps
                                 // max(radius, laser offset +
                                 // kLaserWallClearanceM) of clearance.
  int waypoint_count = 8;        // K random waypoints, [2, 10^6]
  double speed_mps = 0.5;        // driving speed, (0, 10] m/s
  double turn_rate_radps = 1.0;  // in-place turn rate, (0, 20] rad/s
  double laser_rate_hz = 10.0;   // laser records per second, (0, 1000] Hz
  int record_count = 600;        // N laser records, [1, 10^7]
  // true: stop at the route's last waypoint, even before N records.
  // false (default): keep drawing waypoints (same sequence) until N records.
  bool stop_at_route_end = false;

  // Range noise, per beam.
  double range_sigma_m = 0.03;                   // Gaussian sigma, [0, 10] m
  double short_reading_probability = 0.01;       // reading ~ U[0, true range], [0, 1]
  double max_range_dropout_probability = 0.005;  // reading = max range, [0, 1]
  // Moving people (discs ray-cast against); 0 disables them.
  int people_count = 2;           // [0, 1000]
  double people_radius_m = 0.25;  // (0, 2] m
  double people_speed_mps = 1.0;  // walking speed, (0, 10] m/s

  // Odometry noise and drift (fractions are of each increment between
  // two records).
  double odometry_translation_sigma = 0.02;        // multiplicative, [0, 1]
  double odometry_rotation_sigma = 0.02;           // multiplicative, [0, 1]
  double odometry_translation_bias = 0.01;         // scale error (wheel radius), [-0.5, 0.5]
  double odometry_heading_drift_rad_per_m = 0.01;  // heading bias per metre, [-1, 1] rad/m
  // Odometry pose of record 0 (m, m, rad). Unset: kDefaultOdometryFrame
  // composed with the true start pose.
  std::optional<Pose2> odometry_start;

  // Kidnap: record index K in [1, N) at which the true robot has been
  // teleported to a random reachable pose (at least 1 m away when the map
  // allows, uniform heading), after driving its usual step, which the
  // odometry reports; the robot then heads for its next waypoint. -1 = off.
  int kidnap_record = -1;

  // Turns off every noise source: range noise, short readings, people,
  // dropouts, and odometry noise, bias and drift. A kidnap stays as set.
  void DisableNoise();
  bool IsValid(std::string* error) const;
};

struct SimulatedTrace {
  SensorTrace trace;  // format "cmu", options' geometry; odometry poses
  // One per laser record, same times, robot centre in the map frame.
  std::vector<GroundTruthPose> ground_truth;
  // Record index at which the robot had been teleported; -1 if no kidnap
  // happened (disabled, or the route ended first).
  int kidnap_record = -1;
  // The clearance the route kept (m): max(robot radius, laser offset +
  // kLaserWallClearanceM).
  double planning_radius_m = 0.0;
  // The K-waypoint route (map frame); the robot may continue past its end.
  FreeSpaceRoute route;
};

// Throws std::invalid_argument for invalid options and for the route errors
// (no free cell, free space too narrow, fewer than 2 reachable waypoints).
SimulatedTrace SimulateTrace(const OccupancyGrid& grid, const SimulationOptions& options);

}  // namespace rc
