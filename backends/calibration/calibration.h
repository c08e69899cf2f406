#pragma once
// The calibration report (`rcbench calibrate`): the RoboGPU paper's
// reported ratios (REFERENCE.md section 1) beside ours, measured by pricing
// our own recorded workloads in one run, each row with one sentence on why
// ours differs. Nothing is tuned toward the paper's values.
//
//   CalibrationWorkloads w = MakeCalibrationWorkloads(options);  // run once
//   CalibrationReport report = Calibrate(w, params);             // price
//   WriteCalibrationMarkdown(out, report);
//
// Rows, in order: DeliBot (delibot_calibration.h), then the SACT collision
// rows (collision_calibration.h).
#include "backends/backend_params.h"
#include "backends/calibration/calibration_row.h"
#include "backends/calibration/calibration_workloads.h"

namespace rc {

CalibrationReport Calibrate(const CalibrationWorkloads& workloads, const BackendParameters& params);

}  // namespace rc
