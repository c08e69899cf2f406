#pragma once
// A stand-in for pricing in the calibration tests: a speedup of robocore's
// warp buffer depth over 4 (so x0.5 flips it below 1) and a percent change
// that only the SIMT precision moves.
#include <vector>

#include "backends/backend_params.h"
#include "backends/calibration/calibration_row.h"

namespace rc::test {

inline std::vector<CalibrationRow> FakeMeasure(const BackendParameters& p) {
  CalibrationRow speedup;
  speedup.result = "speedup";
  speedup.unit = CalibrationUnit::kSpeedup;
  speedup.ours = 1.5 * p.robocore.unit.warp_buffer_warps / 4.0;
  CalibrationRow change;
  change.result = "change";
  change.unit = CalibrationUnit::kPercentChange;
  change.ours = p.simt.precision == SimtPrecision::kFp32 ? 10.0 : -10.0;
  return {speedup, change};
}

}  // namespace rc::test
