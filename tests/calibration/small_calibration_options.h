#pragma once
// Calibration options small enough for a unit test: a few SACT poses per
// scene and 12 DeliBot records of 40 particles; the shared data when
// present, the generated inputs otherwise.
#include "backends/calibration/calibration_workloads.h"

namespace rc::test {

inline CalibrationOptions SmallCalibrationOptions() {
  CalibrationOptions o;
  o.data_dir = RC_SHARED_DATA_DIR;
  o.particles = 24;
  o.beams = 60;
  o.random_obbs = 200;
  o.min_sact_queries = 700;
  o.run_particles = 40;
  o.run_max_records = 12;
  return o;
}

}  // namespace rc::test
