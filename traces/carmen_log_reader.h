#pragma once
// Reader for CARMEN logs (.clf; CARMEN's logger also writes .log). Format as
// documented in CARMEN's logger header and read by MRPT's carmen_log_tools:
// one message per line, all lengths in m, angles in rad, and every message
// ends with "ipc_timestamp ipc_hostname logger_timestamp".
//   FLASER num_readings r1..rn x y theta odom_x odom_y odom_theta  ts host lts
//   ROBOTLASER1 laser_type start_angle field_of_view angular_resolution
//     maximum_range accuracy remission_mode num_readings r1..rn
//     num_remissions m1..mk laser_x laser_y laser_theta robot_x robot_y
//     robot_theta tv rv forward_safety_dist side_safety_dist turn_axis ts host lts
//   ODOM x y theta tv rv accel ts host lts
//   PARAM name value [ts host lts]
// Laser records become LaserScans: odometry = odom_x/y/theta (FLASER) or
// robot_x/y/theta (ROBOTLASER1), time = ipc_timestamp, ranges as logged.
// ODOM is validated and counted; the laser records already carry odometry.
// '#' lines are comments. PARAM lines and messages of other sensors (RLASER,
// RAWLASERn, ROBOTLASER2, TRUEPOS, SYNC, ...) are skipped and counted.
//
// Geometry.
// - ROBOTLASER1 states it: start_angle, angular_resolution, maximum_range.
// - FLASER does not. First beam at -pi/2 (the robot's right), counter-
//   clockwise, n beams spanning the 180 deg field of view at a step of
//   180/(n - n mod 2) deg: an odd count includes both ends (a SICK LMS gives
//   181 readings at 1 deg, 361 at 0.5 deg); an even count stops one step short
//   of +90 deg, as CMU's 180-beam logs do and as gmapping reads 180-beam
//   FLASER logs. PARAM laser_front_laser_resolution (deg) replaces the step
//   and PARAM robot_front_laser_max (m) the max range, as in MRPT, if they
//   come before the first FLASER.
// - Mount: "x y theta" is the laser pose, so laser pose minus odometry pose
//   (in the robot frame) is the mount. It is taken from the first laser
//   record; every later record must agree, and the laser must face forward on
//   the heading axis (LaserGeometry models nothing else). Logs whose
//   "x y theta" is a corrected pose rather than odometry plus mount fail this
//   check; set laser_offset_forward_m for them.
// ROBOTLASER1 is read in the layout with num_remissions (as MRPT and the
// Freiburg tools read it); a line in the older layout without remissions
// fails with a field error rather than being guessed at. Rear lasers (RLASER,
// ROBOTLASER2) are skipped: MCL here uses one laser.
// A log may hold FLASER or ROBOTLASER1 records, not both: they would be two
// copies of the front laser, and picking one silently could hide a mismatch.
// A FLASER whose num_readings disagrees with the ranges it carries is blamed
// on num_readings (the line's length decides, read from its trailer).
#include <fstream>
#include <memory>
#include <optional>
#include <string>

#include "common/text_fields.h"
#include "traces/laser_record_stream.h"

#include "traces/laser_mount.h"
#include "traces/sensor_trace.h"
#include "traces/trace_read_stats.h"

namespace rc {

struct CarmenLogOptions {
  // FLASER max range unless a PARAM robot_front_laser_max says otherwise: the
  // SICK LMS "no return" threshold, as for the CMU logs.
  double default_max_range_m = 81.83;
  // If set, the laser's forward offset (m); the logged laser pose is then
  // validated as numbers but not used to derive or check the mount.
  std::optional<double> laser_offset_forward_m;
  LaserMountTolerance mount_tolerance;
};

// Throws InputError (file, 1-based line, field) on a malformed message, a
// geometry or beam count that changes between laser records, mixed FLASER and
// ROBOTLASER1 records, a laser record more than a clock glitch earlier than
// the one before (record_fields.h), an inconsistent
// mount, or a log without laser records. Nothing is repaired.
SensorTrace ReadCarmenLog(const std::string& path, const CarmenLogOptions& options = {},
                          TraceReadStats* stats = nullptr);

// The same reader, one laser record at a time.
class CarmenLogStream final : public LaserRecordStream {
 public:
  // Throws InputError if the file cannot be opened.
  CarmenLogStream(const std::string& path, const CarmenLogOptions& options);
  ~CarmenLogStream() override;
  bool Next(LaserScan& scan) override;
  const LaserGeometry& geometry() const override;
  const TraceReadStats& stats() const override { return stats_; }

 private:
  struct State;  // the checks that carry from record to record
  std::ifstream in_;
  LineReader reader_;
  TraceReadStats stats_;
  std::unique_ptr<State> state_;
};

}  // namespace rc
