#pragma once
// The recorded workloads the calibration prices, built once per run
// (DESIGN.md "run once, price many times"): every row, and every parameter
// variant a row needs, prices these same records.
//
//   DeliBot  a first-MCL-update ray batch: particles uniform in the free
//            space of the Wean map (../shared/data/wean/wean.dat) or, when
//            the shared data is absent, of the generated office map; beams
//            fanned over 180 degrees; recorded for march, dda and rm, each
//            with the beam-model leaf.
//   SACT     robot-link OBBs (../shared/data/collision/mpnet_master_obb.csv,
//            or seeded random OBBs in the arm's workspace when absent)
//            against the generated cubby-shelf scene, through its flattened
//            median-split box tree in float (the datapath is FP32; 32-byte
//            nodes), depth-first, no sphere pre-tests.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "maps/occupancy_grid.h"
#include "robocore/kernel_record.h"
#include "robocore/ray_cast.h"

namespace rc {

struct CalibrationOptions {
  std::string data_dir = "../shared/data";  // the shared data; absent files fall back to generated inputs
  int particles = 500;                      // count; RoWild DeliBot
  int beams = 180;                          // count; RoWild DeliBot
  double max_range_m = 10.0;                // m; RoWild DeliBot
  int random_obbs = 700;                    // count; only without the mpnet_master file
  std::uint64_t seed = 7;                   // particles and random OBBs
  bool IsValid(std::string* error) const;
};

struct RayCasterRecord {
  RayCastMethod method = RayCastMethod::kDda;
  KernelRecord record;
};

struct CalibrationWorkloads {
  std::string ray_description;       // which map, how many rays, mean nodes per ray
  std::vector<RayCasterRecord> rays;  // march, dda, rm
  std::string collision_description;  // which OBBs, the scene, nodes per query, collisions
  KernelRecord sact;                  // the shipped SACT program's record
  // The same OBBs as the sphere robot (one bounding sphere each,
  // programs/sphere_aabb.asm) on the same tree, and its false collisions
  // against the SACT's answers (robocore/collision/sphere_robot.h).
  KernelRecord spheres;
  std::uint64_t sphere_false_collisions = 0;  // count of OBBs
  std::uint64_t sphere_obb_collisions = 0;    // count of OBBs the SACT finds colliding
};

// Throws UsageError for invalid options, InputError for unreadable data.
CalibrationWorkloads MakeCalibrationWorkloads(const CalibrationOptions& options);

}  // namespace rc
