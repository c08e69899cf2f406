#pragma once
// The SACT collision rows, priced per preset on recorded traversals and set
// side by side (artifact preset | ours):
//   RoboCore vs CUDA (SIMT), with and without the kernel launch
//   TTA+-cr vs TTA+, RoboCore vs TTA+-cr, TTA+-p vs TTA+
//   energy, RoboCore vs CUDA
//   early exit: average computation latency per query, RoboCore with vs
//     without it (the same datapath with RETURN_IFs dropped)
//   SACT unit latency x0.5 and x2 (RoboCoreParams::sact_latency_scale,
//     relative to the preset) -> total time change
//   the fully parallel SACT and two of each SACT unit
//     (sact_datapath_variants.h) -> total time change
//   the sphere robot (programs/sphere_aabb.asm) on RoboCore vs the OBB SACT
//     on CUDA, with its false-collision rate
// At paper scale the four scenes' batches are summed (one launch each), and
// RoboCore vs CUDA is also given per scene; the small batch is one launch.
// Times other than the "incl. launch" row exclude the kernel launch, a
// fixed cost; they compare what the queries themselves cost.
#include <vector>

#include "backends/backend_preset.h"
#include "backends/calibration/calibration_row.h"
#include "backends/calibration/calibration_workloads.h"

namespace rc {

// `artifact` and `ours` the same object: priced once.
std::vector<CalibrationRow> CollisionRows(const CalibrationWorkloads& workloads, const BackendPreset& artifact,
                                          const BackendPreset& ours);

}  // namespace rc
