#pragma once
// In-memory sensor trace: laser scans, each with the odometry pose at which it
// was taken. All units SI (m, rad, s) whatever the file format used.
//
// Every supported format (CMU robotdata .log, RoWild's one-line log, CARMEN
// .clf FLASER) carries the robot's odometry pose on each laser record, which
// is all the odometry motion model needs (it uses consecutive differences).
#include <cstddef>
#include <string>
#include <vector>

#include "common/angles.h"

namespace rc {

// Beam i (0-based) points at angle_min_rad + i * angle_increment_rad relative
// to the robot heading, from a sensor mounted offset_forward_m ahead of the
// robot centre on its heading axis.
struct LaserGeometry {
  int beam_count = 180;
  double angle_min_rad = -kPi / 2.0;         // first beam: the robot's right
  double angle_increment_rad = kPi / 180.0;  // counter-clockwise (right to left)
  double max_range_m = 81.83;                // readings >= this are "no return"
  double offset_forward_m = 0.25;            // laser ahead of the robot centre

  double BeamAngle(int i) const { return angle_min_rad + i * angle_increment_rad; }
};

struct LaserScan {
  double time_s = 0.0;  // timestamp from the log (0 if the format has none)
  Pose2 odometry;       // robot pose in the odometry frame (m, rad)
  std::vector<float> ranges_m;
  long source_line = 0;  // 1-based line in the trace file, for messages
};

struct SensorTrace {
  std::string source_path;
  std::string format;  // "cmu", "rowild", "carmen", "rawlog"
  LaserGeometry geometry;
  std::vector<LaserScan> scans;
};

}  // namespace rc
