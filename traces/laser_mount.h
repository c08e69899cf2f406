#pragma once
// Where the laser sits on the robot, as measured from logs that record both
// the robot pose and the laser pose of each scan (CMU L, CARMEN FLASER and
// ROBOTLASER1). LaserGeometry models only a forward offset on the heading
// axis, so a reader checks every record against that model instead of
// trusting one record or silently dropping a sideways or angular offset.
#include <string>

#include "common/angles.h"
#include "common/text_fields.h"

namespace rc {

// The laser pose expressed in the robot frame (x forward, y left).
struct LaserMountOffset {
  double forward_m = 0.0;
  double lateral_m = 0.0;
  double heading_rad = 0.0;  // wrapped to (-pi, pi]
};

LaserMountOffset MeasureMountOffset(const Pose2& robot, const Pose2& laser);

// The logs print poses to 1e-6 cm and rad, so the measured offset varies by
// about 1e-6 m between records. The defaults leave room for coarser loggers
// while still catching a wrong mount (centimetres) or a rotated laser.
struct LaserMountTolerance {
  double position_m = 0.005;
  double heading_rad = 1e-3;
};

struct LaserMountStats {
  long samples = 0;
  double min_forward_m = 0.0;
  double max_forward_m = 0.0;
  double max_abs_lateral_m = 0.0;
  double max_abs_heading_rad = 0.0;

  void Add(const LaserMountOffset& offset);
};

// Throws InputError at the reader's current line unless `measured` is within
// `tolerance` of a laser `expected_forward_m` ahead on the heading axis.
// position_field / heading_field name the record's laser pose fields;
// expected_source says where the expectation came from, for the message.
void CheckMountOffset(const LineReader& reader, const LaserMountOffset& measured, double expected_forward_m,
                      const LaserMountTolerance& tolerance, const std::string& position_field,
                      const std::string& heading_field, const std::string& expected_source);

// A log that records both poses states its own mount: the readers take it
// from the first laser record, rounded to kMountResolutionM, and require
// every record (the first included) to agree with it within the tolerance.
// So a log of any robot is read, and only a mount that is inconsistent
// within the file, or not on the heading axis, is refused.
//
// kMountResolutionM: 0.1 mm, range (0, 1 mm]. Source: logged poses jitter by
// about 1e-8 m between records (CMU logs print 1e-6 cm), and 0.1 mm is a
// thousandth of the 10 cm cells the ray casters step through; rounding makes
// the Wean logs' 25.0000 +- 0.0001 cm mount exactly 0.25 m.
inline constexpr double kMountResolutionM = 1e-4;
double RoundMountOffset(double forward_m);

}  // namespace rc
