#include "backends/calibration/calibration.h"

#include "backends/calibration/collision_calibration.h"
#include "backends/calibration/delibot_calibration.h"

namespace rc {

namespace {

CalibrationReport Report(const CalibrationWorkloads& workloads, const BackendPreset& artifact,
                         const BackendPreset& ours, bool include_runs) {
  CalibrationReport report;
  report.ours_name = ours.name;
  report.workload_notes = workloads.notes;
  report.rows = DelibotRows(workloads, artifact, ours, &report.workload_notes, include_runs);
  for (CalibrationRow& row : CollisionRows(workloads, artifact, ours)) report.rows.push_back(std::move(row));
  return report;
}

}  // namespace

CalibrationReport Calibrate(const CalibrationWorkloads& workloads, const BackendPreset& artifact,
                            const BackendPreset& ours) {
  return Report(workloads, artifact, ours, true);
}

CalibrationReport CalibrateOneColumn(const CalibrationWorkloads& workloads, const BackendPreset& preset,
                                     bool include_runs) {
  return Report(workloads, preset, preset, include_runs);  // the row builders price a shared preset once
}

}  // namespace rc
