#pragma once
// What a trace reader saw besides the laser scans it returns, so the command
// line can report it and tests can check it.
#include "traces/laser_mount.h"
#include "traces/record_fields.h"

namespace rc {

struct TraceReadStats {
  long laser_records = 0;     // records turned into LaserScans
  long odometry_records = 0;  // CMU "O" / CARMEN "ODOM": validated, not used
                              // (each laser record carries its own odometry pose)
  long skipped_records = 0;   // CARMEN PARAM lines and messages of other sensors
  // Laser pose relative to the robot, measured on every record of a format
  // that logs both poses (CMU L, CARMEN FLASER/ROBOTLASER1); empty otherwise.
  LaserMountStats laser_mount;
  // Laser records whose time steps back by less than kMaxClockGlitchS
  // (record_fields.h): kept as logged, reported as a warning.
  TimeGlitchStats time_glitches;
};

}  // namespace rc
