#include "backends/calibration/calibration.h"

#include "backends/calibration/collision_calibration.h"
#include "backends/calibration/delibot_calibration.h"

namespace rc {

CalibrationReport Calibrate(const CalibrationWorkloads& workloads, const BackendParameters& params) {
  CalibrationReport report;
  report.workload_notes = {workloads.ray_description, workloads.collision_description};
  report.rows = DelibotRows(workloads, params);
  for (CalibrationRow& row : CollisionRows(workloads, params)) report.rows.push_back(std::move(row));
  return report;
}

}  // namespace rc
