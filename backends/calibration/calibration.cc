#include "backends/calibration/calibration.h"

#include "backends/calibration/collision_calibration.h"
#include "backends/calibration/delibot_calibration.h"

namespace rc {

CalibrationReport Calibrate(const CalibrationWorkloads& workloads, const BackendPreset& artifact,
                            const BackendPreset& ours) {
  CalibrationReport report;
  report.ours_name = ours.name;
  report.workload_notes = workloads.notes;
  report.rows = DelibotRows(workloads, artifact, ours, &report.workload_notes);
  for (CalibrationRow& row : CollisionRows(workloads, artifact, ours)) report.rows.push_back(std::move(row));
  return report;
}

CalibrationReport CalibrateOneColumn(const CalibrationWorkloads& workloads, const BackendPreset& preset) {
  return Calibrate(workloads, preset, preset);  // the row builders price a shared preset once
}

}  // namespace rc
