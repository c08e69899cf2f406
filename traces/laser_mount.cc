#include "traces/laser_mount.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace rc {

LaserMountOffset MeasureMountOffset(const Pose2& robot, const Pose2& laser) {
  const double dx = laser.x - robot.x;
  const double dy = laser.y - robot.y;
  const double c = std::cos(robot.theta);
  const double s = std::sin(robot.theta);
  LaserMountOffset offset;
  offset.forward_m = c * dx + s * dy;
  offset.lateral_m = -s * dx + c * dy;
  offset.heading_rad = WrapAngle(laser.theta - robot.theta);
  return offset;
}

void LaserMountStats::Add(const LaserMountOffset& offset) {
  if (samples == 0) {
    min_forward_m = max_forward_m = offset.forward_m;
  } else {
    min_forward_m = std::min(min_forward_m, offset.forward_m);
    max_forward_m = std::max(max_forward_m, offset.forward_m);
  }
  max_abs_lateral_m = std::max(max_abs_lateral_m, std::abs(offset.lateral_m));
  max_abs_heading_rad = std::max(max_abs_heading_rad, std::abs(offset.heading_rad));
  ++samples;
}

void CheckMountOffset(const LineReader& reader, const LaserMountOffset& measured, double expected_forward_m,
                      const LaserMountTolerance& tolerance, const std::string& position_field,
                      const std::string& heading_field, const std::string& expected_source) {
  if (std::abs(measured.forward_m - expected_forward_m) > tolerance.position_m ||
      std::abs(measured.lateral_m) > tolerance.position_m)
    reader.Fail(position_field, fmt::format("laser pose puts the laser {:.6f} m ahead and {:.6f} m left of the robot; "
                                            "expected {:.6f} m ahead on the heading axis ({}; tolerance {:.6f} m)",
                                            measured.forward_m, measured.lateral_m, expected_forward_m, expected_source,
                                            tolerance.position_m));
  if (std::abs(measured.heading_rad) > tolerance.heading_rad)
    reader.Fail(heading_field, fmt::format("laser heading differs from the robot heading by {:.6f} rad (tolerance "
                                           "{:.6f} rad); a rotated laser mount is not modelled",
                                           measured.heading_rad, tolerance.heading_rad));
}

double RoundMountOffset(double forward_m) {
  // Dividing by the step count per metre (exactly 10000) keeps values such
  // as 0.25 exact; multiplying by 1e-4 would not.
  const double steps_per_m = std::round(1.0 / kMountResolutionM);
  return std::round(forward_m * steps_per_m) / steps_per_m;
}

}  // namespace rc
