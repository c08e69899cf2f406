#include "workloads/delibot/scan_consistency.h"

#include <cmath>

#include "workloads/delibot/sensor_model.h"

namespace rc {

ScanConsistency MeasureScanConsistency(const RayCastScene& exact_scene, const Pose2& robot,
                                       const LaserScan& scan, const LaserGeometry& geometry,
                                       double max_range_m, double tolerance_m) {
  ScanConsistency out;
  const Pose2 sensor = SensorPose(robot, geometry);
  for (int b = 0; b < geometry.beam_count; ++b) {
    const double z = scan.ranges_m[b];
    if (z >= max_range_m) continue;
    const RayHit hit = CastRay(exact_scene, sensor.x, sensor.y, sensor.theta + geometry.BeamAngle(b), max_range_m);
    ++out.beams_used;
    if (std::abs(z - hit.range_m) <= tolerance_m) ++out.beams_within;
  }
  return out;
}

}  // namespace rc
