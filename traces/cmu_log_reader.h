#pragma once
// Reader for the CMU robot-localization logs (robotdata1..4.log, see
// shared/data/wean/instruct.txt). One record per line, cm and rad:
//   O x y theta ts                              odometry
//   L x y theta xl yl thetal r1 .. r180 ts      laser, with the interpolated
//                                               robot pose and laser pose
// Each L record becomes a LaserScan: odometry = the robot pose (x y theta),
// time = ts, ranges converted to metres, geometry = CmuLaserGeometry().
// O records are validated and counted but not returned: the L pose is
// already the odometry interpolated at the scan time, which is all the
// motion model needs.
#include <string>

#include "traces/laser_mount.h"
#include "traces/sensor_trace.h"
#include "traces/trace_read_stats.h"

namespace rc {

struct CmuLogOptions {
  // The Wean Hall robot's mount (instruct.txt: "approximately 25 cm"). The
  // laser pose of every L record must agree with it within mount_tolerance;
  // logs of a robot with another mount must say so here.
  double laser_offset_forward_m = 0.25;
  LaserMountTolerance mount_tolerance;
};

// Throws InputError (file, 1-based line, field) on anything malformed: an
// unknown record type, a missing or extra field, a non-numeric, NaN or inf
// value, a negative range, laser records out of time order, a laser pose that
// contradicts the mount, or a log without L records. Nothing is repaired.
SensorTrace ReadCmuLog(const std::string& path, const CmuLogOptions& options = {},
                       TraceReadStats* stats = nullptr);

}  // namespace rc
