#pragma once
// The DeliBot rows: RoboCore vs CUDA cores (paper: 1.10x faster) and
// RoboCore vs TTA+ (paper: 1.20x faster) on the first-MCL-update ray batch,
// one pair of rows per ray caster (march, dda, rm). Times include the
// kernel launch: an MCL update is one launch, as in the paper's runs.
#include <vector>

#include "backends/backend_params.h"
#include "backends/calibration/calibration_row.h"
#include "backends/calibration/calibration_workloads.h"

namespace rc {

std::vector<CalibrationRow> DelibotRows(const CalibrationWorkloads& workloads, const BackendParameters& params);

}  // namespace rc
