#pragma once
// The SACT collision rows, all priced on the one recorded traversal of the
// collision workload (calibration_workloads.h):
//   RoboCore vs CUDA (SIMT), with and without the kernel launch
//   TTA+-cr vs TTA+, RoboCore vs TTA+-cr, TTA+-p vs TTA+
//   energy, RoboCore vs CUDA
//   early exit: average computation latency per query, RoboCore with vs
//     without it (the same datapath with RETURN_IFs dropped)
//   SACT unit latency x0.5 and x2 (RoboCoreParams::sact_latency_scale,
//     relative to the given parameters) -> total time change
//   the fully parallel SACT and two of each SACT unit
//     (sact_datapath_variants.h) -> total time change
//   the sphere robot (workloads.spheres, programs/sphere_aabb.asm) on
//     RoboCore vs the OBB SACT on CUDA, with its false-collision rate
// Times other than the "incl. launch" row exclude the kernel launch, a
// fixed cost a batch of a few dozen queries cannot amortize; they compare
// what the queries themselves cost.
#include <vector>

#include "backends/backend_params.h"
#include "backends/calibration/calibration_row.h"
#include "backends/calibration/calibration_workloads.h"

namespace rc {

std::vector<CalibrationRow> CollisionRows(const CalibrationWorkloads& workloads, const BackendParameters& params);

}  // namespace rc
