#pragma once
// The laser of the CMU Wean Hall robot, which both the CMU robotdata logs and
// RoWild's one-line logs describe (neither file states it; instruct.txt does).
#include "traces/sensor_trace.h"

namespace rc {

// Conversion used by every reader and writer of the centimetre formats.
// Division by 100 is correctly rounded, unlike multiplication by 0.01, so a
// written-then-read value comes back bit-identical.
inline double CentimetresToMetres(double cm) { return cm / 100.0; }
inline double MetresToCentimetres(double m) { return m * 100.0; }

// The SICK LMS reports ranges in whole cm; values from 8183 cm up are not
// distances but status codes. The logs contain 8183 ("beyond range"), 8187,
// 8189 and 8191 (signal errors, no echo); the largest real echo in the four
// robotdata logs is 57.67 m. So 81.83 m is the "no return" threshold, and
// every code maps to "no return" under LaserGeometry's ">= max" rule.
inline constexpr double kCmuNoReturnCm = 8183.0;

// instruct.txt: 180 readings from the right (-90 deg) to the left, one per
// degree, counter-clockwise; the laser sits about 25 cm ahead of the robot
// centre. The logs' own laser poses (xl, yl, thetal) put it 25.0000 +- 0.0001
// cm ahead on the heading axis in every L record of the four logs (checked by
// the reader on each record; the measured value is pinned in a test).
inline LaserGeometry CmuLaserGeometry() {
  LaserGeometry g;
  g.beam_count = 180;
  g.angle_min_rad = -kPi / 2.0;
  g.angle_increment_rad = kPi / 180.0;
  g.max_range_m = CentimetresToMetres(kCmuNoReturnCm);
  g.offset_forward_m = 0.25;
  return g;
}

}  // namespace rc
