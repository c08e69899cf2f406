#pragma once
// The calibration report (`rcbench calibrate`): the RoboGPU paper's
// reported ratios (REFERENCE.md section 1) beside ours, measured by pricing
// our own recorded workloads in one run under two presets, the artifact's
// (backends/presets/artifact.json) and ours (defaults, or a --params file),
// each row with its workload's size and one computed sentence on why ours
// differs (why_sentences.h). Nothing is tuned toward the paper's values.
//
//   CalibrationWorkloads w = MakeCalibrationWorkloads(options);  // run once
//   CalibrationReport report = Calibrate(w, ArtifactPreset(), DefaultPreset());
//   WriteCalibrationMarkdown(out, report);
//
// Rows, in order: DeliBot (delibot_calibration.h: whole runs, then the
// first update), then SACT (collision_calibration.h: per scene, all scenes,
// then the small batch).
#include "backends/backend_preset.h"
#include "backends/calibration/calibration_row.h"
#include "backends/calibration/calibration_workloads.h"

namespace rc {

CalibrationReport Calibrate(const CalibrationWorkloads& workloads, const BackendPreset& artifact,
                            const BackendPreset& ours);
// The report priced once, under `preset` (both columns hold its values):
// what the sensitivity sweep measures per variant, at half the cost.
// Without `include_runs`, no whole DeliBot run rows (the sweep prices those
// for every variant at once: DelibotRunRowsUnderVariants).
CalibrationReport CalibrateOneColumn(const CalibrationWorkloads& workloads, const BackendPreset& preset,
                                     bool include_runs = true);

}  // namespace rc
