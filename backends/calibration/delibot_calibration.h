#pragma once
// The DeliBot rows: RoboCore vs CUDA cores (paper: 1.10x faster) and
// RoboCore vs TTA+ (paper: 1.20x faster), priced per preset:
//   paper scale  whole runs (RunDelibot with the march ray caster, every
//                update priced on every backend, totals over the run), one
//                pair of rows per run (demo, robotdata1);
//   small batch  the first-update batch, one pair of rows per ray caster
//                (march, dda, rm).
// Each preset records with its own kernel choices (the grid's cell size and
// the march program), so the artifact preset prices its 8-byte cells and
// 7-op march. Times include the kernel launch: an MCL update is one launch
// (and an injection check's replayed scans one more each), as in the
// paper's runs.
#include <vector>

#include "backends/backend_preset.h"
#include "backends/calibration/calibration_row.h"
#include "backends/calibration/calibration_workloads.h"

namespace rc {

// `artifact` and `ours` the same object: priced once. Without
// `include_runs`, the small-batch rows only.
std::vector<CalibrationRow> DelibotRows(const CalibrationWorkloads& workloads, const BackendPreset& artifact,
                                        const BackendPreset& ours, std::vector<std::string>* notes = nullptr,
                                        bool include_runs = true);

// The whole-run rows (both columns the variant's), per variant, for the
// sensitivity sweep: each run is filtered once per placement of warps on
// SMs among the variants (once, unless a variant moves gpu.sms,
// warps_per_block, warp_size or sector_bytes), recorded with `kernel`'s
// choices, and every update is priced under every variant as it is
// recorded. Each variant's rows equal DelibotRows' for a preset of that
// variant and `kernel` (tests/calibration/delibot_run_sweep_test.cc).
std::vector<std::vector<CalibrationRow>> DelibotRunRowsUnderVariants(const CalibrationWorkloads& workloads,
                                                                     const RayKernelChoices& kernel,
                                                                     const std::vector<BackendParameters>& variants);

}  // namespace rc
