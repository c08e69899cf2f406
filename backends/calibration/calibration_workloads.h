#pragma once
// The workloads the calibration prices, built once per run (DESIGN.md "run
// once, price many times"). What does not depend on the preset is recorded
// here; what does (the DeliBot grid's cell size and march program, a
// preset's "kernel" choices) is recorded per preset from the inputs kept
// here (delibot_calibration.h).
//
// Paper scale:
//   SACT     four MPiNet-like scenes (mpinet_like_scenes.h), each an
//            OctoMap octree of 1000-2000 nodes, against >= min_sact_queries
//            jittered arm-link OBBs (double precision, as the host kernels
//            and the artifact's CUDA baseline: 64-byte nodes), depth-first,
//            no sphere pre-tests; and the same OBBs as the sphere robot.
//   DeliBot  whole runs (RunDelibot, every update priced on every backend):
//            the demo (generated office map, simulated 400-record trace)
//            and, with the shared data, robotdata1 on the Wean map.
// Small batch (kept for comparison with earlier reports):
//   DeliBot  one first-MCL-update ray batch: particles uniform in the free
//            space of the Wean map (or the generated office map), beams
//            fanned over 180 degrees, for march, dda and rm.
//   SACT     the mpnet_master OBBs (70; or seeded random OBBs when the
//            file is absent) against the generated cubby-shelf scene's
//            median-split box tree in float (32-byte nodes).
#include <cstdint>
#include <string>
#include <vector>

#include "backends/calibration/mpinet_like_scenes.h"
#include "maps/occupancy_grid.h"
#include "robocore/collision/collision_summary.h"
#include "robocore/kernel_record.h"
#include "robocore/ray_batch.h"
#include "traces/sensor_trace.h"

namespace rc {

struct CalibrationOptions {
  std::string data_dir = "../shared/data";  // the shared data; absent files fall back to generated inputs
  std::uint64_t seed = 7;                   // particles, scenes, OBB jitter, random OBBs
  // Small batch.
  int particles = 500;        // count; RoWild DeliBot
  int beams = 180;            // count; RoWild DeliBot
  double max_range_m = 10.0;  // m; RoWild DeliBot
  int random_obbs = 700;      // count; only without the mpnet_master file
  // Paper scale.
  int min_sact_queries = 10000;  // per scene, count: the paper-scale batch floor
  std::vector<MpinetSceneKind> scenes = {std::begin(kMpinetSceneKinds), std::end(kMpinetSceneKinds)};
  bool delibot_runs = true;  // price whole DeliBot runs
  int run_particles = 500;   // count; RoWild DeliBot
  int run_beam_step = 6;     // every K-th of 180 beams (30 beams), rcbench delibot's default
  long run_max_records = 0;  // 0: the whole trace
  bool IsValid(std::string* error) const;
};

struct SactSceneWorkload {
  MpinetSceneKind kind = MpinetSceneKind::kCubby;
  double resolution_m = 0;
  std::uint32_t octree_nodes = 0;  // the artifact's node count (cells with children)
  std::uint64_t box_nodes = 0;     // nodes of the box tree the kernels fetch
  CollisionSummary summary;
  KernelRecord sact;     // the shipped SACT program's record
  KernelRecord spheres;  // one bounding sphere per OBB
  std::uint64_t sphere_false_collisions = 0;
  std::string Size() const;  // "10010 queries x 23.4 nodes, 1312-node octree (8745 box nodes)"
};

struct DelibotRunWorkload {
  std::string name;  // "demo", "robotdata1"
  OccupancyGrid grid;
  SensorTrace trace;
};

struct CalibrationWorkloads {
  CalibrationOptions options;
  std::vector<std::string> notes;  // one line per workload, for the report's header

  // Paper scale.
  std::vector<SactSceneWorkload> scenes;
  std::vector<DelibotRunWorkload> runs;

  // Small batch.
  OccupancyGrid ray_grid;  // Wean, or the generated office map
  RayBatch first_update;   // every particle uniform in free space
  KernelRecord sact;       // mpnet_master (or random) OBBs vs the shelf tree
  KernelRecord spheres;
  std::uint64_t sphere_false_collisions = 0;
  std::uint64_t sphere_obb_collisions = 0;
};

// Throws UsageError for invalid options, InputError for unreadable data.
CalibrationWorkloads MakeCalibrationWorkloads(const CalibrationOptions& options);

// The arm whose links the SACT scenes are queried with: the mpnet_master
// poses from options.data_dir, or, without that file, seeded random
// link-size OBBs, one per pose. Throws InputError for an unreadable file.
struct ArmLinkPoses {
  std::vector<std::vector<Obbd>> poses;  // a pose's links, base to tip
  std::string source;                    // where they came from, for the report
  std::string path;                      // the mpnet_master file looked for
  bool from_file = false;                // false: the seeded random OBBs
};
ArmLinkPoses MakeArmLinkPoses(const CalibrationOptions& options);

// A paper-scale SACT scene's inputs: the scene's octree and at least
// options.min_sact_queries jittered arm-link OBBs aimed across it (seed:
// options.seed + the scene kind). SactSceneWorkload is priced from these.
struct SactSceneInputs {
  SceneOctree octree;
  std::vector<Obbd> queries;
};
SactSceneInputs MakeSactSceneInputs(MpinetSceneKind kind, const std::vector<std::vector<Obbd>>& poses,
                                    const CalibrationOptions& options);

}  // namespace rc
