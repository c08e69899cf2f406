#pragma once
// A ground-truth-free measure of how well an estimate explains a scan: the
// fraction of beams whose measured range lies within k sigma of the range
// ray-cast from the estimated pose. Beams at or beyond the model's maximum
// range are left out (a no-return says little), and so are beams whose ray
// stops at an unknown cell: the map does not say where the obstacle there
// is, so the beam can neither confirm nor refute the pose (Wean Hall's
// doorways are unknown cells; without this rule a robot correctly placed in
// a doorway scores as lost). On real logs without ground
// truth, a filter that has converged to the right place keeps this high; a
// filter stuck in a wrong place (or a wrongly read map) cannot.
#include "common/angles.h"
#include "robocore/ray_cast.h"
#include "traces/sensor_trace.h"

namespace rc {

struct ScanConsistency {
  int beams_used = 0;
  int beams_within = 0;
  int beams_unknown = 0;  // left out: the ray stopped at an unknown cell
  double Fraction() const { return beams_used > 0 ? static_cast<double>(beams_within) / beams_used : 0.0; }
};

ScanConsistency MeasureScanConsistency(const RayCastScene& exact_scene, const Pose2& robot, const LaserScan& scan,
                                       const LaserGeometry& geometry, double max_range_m, double tolerance_m);

}  // namespace rc
