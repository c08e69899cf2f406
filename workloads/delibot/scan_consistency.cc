#include "workloads/delibot/scan_consistency.h"

#include <cmath>

#include "workloads/delibot/sensor_model.h"

namespace rc {
namespace {

// The cell just beyond the ray's stopping point (a quarter cell past it) is
// the cell that stopped it.
bool StopsInUnknownSpace(const OccupancyGrid& grid, const Pose2& sensor, double angle, double range_m) {
  const double reach = range_m + 0.25 * grid.resolution_m();
  const int ix = static_cast<int>(std::floor((sensor.x + reach * std::cos(angle)) / grid.resolution_m()));
  const int iy = static_cast<int>(std::floor((sensor.y + reach * std::sin(angle)) / grid.resolution_m()));
  return grid.Contains(ix, iy) && grid.At(ix, iy) == CellState::kUnknown;
}

}  // namespace

ScanConsistency MeasureScanConsistency(const RayCastScene& exact_scene, const Pose2& robot, const LaserScan& scan,
                                       const LaserGeometry& geometry, double max_range_m, double tolerance_m) {
  ScanConsistency out;
  const Pose2 sensor = SensorPose(robot, geometry);
  for (int b = 0; b < geometry.beam_count; ++b) {
    const double z = scan.ranges_m[b];
    if (z >= max_range_m) continue;
    const double angle = sensor.theta + geometry.BeamAngle(b);
    const RayHit hit = CastRay(exact_scene, sensor.x, sensor.y, angle, max_range_m);
    if (hit.range_m < max_range_m && StopsInUnknownSpace(exact_scene.grid(), sensor, angle, hit.range_m)) {
      ++out.beams_unknown;
      continue;
    }
    ++out.beams_used;
    if (std::abs(z - hit.range_m) <= tolerance_m) ++out.beams_within;
  }
  return out;
}

}  // namespace rc
