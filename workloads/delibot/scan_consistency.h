#pragma once
// A ground-truth-free measure of how well an estimate explains a scan: the
// fraction of beams whose measured range lies within k sigma of the range
// ray-cast from the estimated pose. Beams at or beyond the model's maximum
// range are left out (a no-return says little). On real logs without ground
// truth, a filter that has converged to the right place keeps this high; a
// filter stuck in a wrong place (or a wrongly read map) cannot.
#include "common/angles.h"
#include "robocore/ray_cast.h"
#include "traces/sensor_trace.h"

namespace rc {

struct ScanConsistency {
  int beams_used = 0;
  int beams_within = 0;
  double Fraction() const { return beams_used > 0 ? static_cast<double>(beams_within) / beams_used : 0.0; }
};

ScanConsistency MeasureScanConsistency(const RayCastScene& exact_scene, const Pose2& robot,
                                       const LaserScan& scan, const LaserGeometry& geometry,
                                       double max_range_m, double tolerance_m);

}  // namespace rc
