#include "backends/calibration/calibration_workloads.h"

#include <cmath>
#include <filesystem>

#include <fmt/format.h>

#include <Eigen/Geometry>

#include "backends/calibration/sact_kernel_record.h"
#include "common/angles.h"
#include "common/input_error.h"
#include "common/random_stream.h"
#include "maps/cmu_map_loader.h"
#include "maps/office_map_generator.h"
#include "robocore/collision/box_csv.h"
#include "robocore/collision/shelf_scene.h"
#include "robocore/collision/sphere_robot.h"
#include "traces/trace_reader.h"
#include "workloads/delibot/trace_simulator.h"

namespace rc {
namespace {

const char* const kWeanMap = "wean/wean.dat";
const char* const kRobotData1 = "wean/robotdata1.log";
const char* const kRobotObbs = "collision/mpnet_master_obb.csv";
constexpr int kDemoRecords = 400;  // rcbench delibot's built-in demo (workloads/rcbench/demo_inputs.cc)

// The first MCL update: every particle uniform in free space, which is when
// rays are longest (the paper's "early iterations" regime).
RayBatch UniformParticleBeams(const OccupancyGrid& grid, const CalibrationOptions& o) {
  RandomStream s(o.seed, StreamPurpose::kInitialization, 0, 0);
  RayBatch batch;
  batch.max_range_m = o.max_range_m;
  for (int placed = 0; placed < o.particles;) {
    const double x = s.Uniform(0, grid.extent_x_m()), y = s.Uniform(0, grid.extent_y_m());
    if (!grid.IsFreePoint(x, y)) continue;
    const double heading = s.Uniform(-kPi, kPi);
    for (int k = 0; k < o.beams; ++k)
      batch.queries.push_back({x, y, heading - kPi / 2 + (o.beams > 1 ? kPi * k / (o.beams - 1) : 0.0)});
    ++placed;
  }
  return batch;
}

// Seeded OBBs of robot-link size in the arm's workspace (both shelves and
// the space between them), uniformly random orientation (normalized
// Gaussian quaternion).
std::vector<Obbd> RandomWorkspaceObbs(const CalibrationOptions& o) {
  RandomStream s(o.seed, StreamPurpose::kTest, 0, 1);
  std::vector<Obbd> obbs(static_cast<std::size_t>(o.random_obbs));
  for (Obbd& b : obbs) {
    b.centre = {s.Uniform(-0.9, 0.9), s.Uniform(-0.7, 0.7), s.Uniform(0.05, 1.1)};
    Eigen::Quaterniond q(s.Gaussian(), s.Gaussian(), s.Gaussian(), s.Gaussian());
    b.axes = q.normalized().toRotationMatrix();
    b.half = {s.Uniform(0.03, 0.12), s.Uniform(0.03, 0.12), s.Uniform(0.03, 0.16)};
  }
  return obbs;
}

SactSceneWorkload SceneWorkload(MpinetSceneKind kind, const std::vector<std::vector<Obbd>>& poses,
                                const CalibrationOptions& o) {
  const SactSceneInputs inputs = MakeSactSceneInputs(kind, poses, o);
  const SceneOctree& octree = inputs.octree;
  const std::vector<Obbd>& queries = inputs.queries;
  const FlatBoxTree<double> tree(octree.tree);
  SactSceneWorkload w;
  w.kind = kind;
  w.resolution_m = octree.resolution_m;
  w.octree_nodes = octree.octree_nodes;
  w.box_nodes = tree.nodes().size();
  const CollisionBatch batch = CollideBatch(tree, queries, CollisionOptions<double>{});
  w.summary = Summarize(batch);
  w.sact = SactKernelRecord(batch);
  w.spheres = SphereKernelRecord(CollideSphereBatch(tree, queries, 1, TraversalOrder::kDepthFirst).spheres);
  w.sphere_false_collisions = CompareSphereRobot(tree, queries, CollisionOptions<double>{}, 1).false_collisions;
  return w;
}

}  // namespace

ArmLinkPoses MakeArmLinkPoses(const CalibrationOptions& o) {
  const std::string robot_path = o.data_dir + "/" + kRobotObbs;
  ArmLinkPoses arm;
  arm.path = robot_path;
  arm.from_file = std::filesystem::exists(robot_path);
  std::size_t links = 0;
  if (arm.from_file) {
    long pose = -1;
    for (const RobotObb& r : ReadObbCsv(robot_path)) {
      if (arm.poses.empty() || r.pose != pose) arm.poses.emplace_back(), pose = r.pose;
      arm.poses.back().push_back(r.obb);
      ++links;
    }
    arm.source = "the " + std::to_string(arm.poses.size()) + " mpnet_master arm poses (" + std::to_string(links) +
                 " link OBBs, " + robot_path + ")";
  } else {
    for (const Obbd& b : RandomWorkspaceObbs(o)) arm.poses.push_back({b});
    arm.source = std::to_string(arm.poses.size()) + " seeded random link-size OBBs (no " + robot_path + ")";
  }
  return arm;
}

SactSceneInputs MakeSactSceneInputs(MpinetSceneKind kind, const std::vector<std::vector<Obbd>>& poses,
                                    const CalibrationOptions& o) {
  const std::uint64_t seed = o.seed + static_cast<std::uint64_t>(kind);
  SactSceneInputs inputs;
  inputs.octree = BuildSceneOctree(kind, seed);
  std::size_t links = 0;
  for (const auto& pose : poses) links += pose.size();
  const int yaws = static_cast<int>((static_cast<std::size_t>(o.min_sact_queries) + links - 1) / links);
  inputs.queries = JitteredArmQueries(poses, yaws, inputs.octree, seed);
  return inputs;
}

std::string SactSceneWorkload::Size() const {
  return fmt::format("{} queries x {:.1f} nodes; {}-node octree ({} box nodes, {:.3g} m voxels)", sact.query_count(),
                     summary.nodes_per_query_mean, octree_nodes, box_nodes, resolution_m);
}

bool CalibrationOptions::IsValid(std::string* error) const {
  auto fail = [&](const char* what) {
    if (error) *error = what;
    return false;
  };
  if (particles < 1 || beams < 1) return fail("calibration: particles and beams must be >= 1");
  if (!(max_range_m > 0)) return fail("calibration: max range must be > 0");
  if (random_obbs < 1) return fail("calibration: random OBB count must be >= 1");
  if (min_sact_queries < 1) return fail("calibration: the SACT batch needs >= 1 query");
  if (run_particles < 1 || run_beam_step < 1 || run_max_records < 0)
    return fail("calibration: DeliBot runs need >= 1 particle, a beam step >= 1 and max records >= 0");
  return true;
}

CalibrationWorkloads MakeCalibrationWorkloads(const CalibrationOptions& o) {
  std::string error;
  if (!o.IsValid(&error)) throw UsageError(error);
  CalibrationWorkloads w;
  w.options = o;

  const ArmLinkPoses arm = MakeArmLinkPoses(o);
  const std::vector<std::vector<Obbd>>& poses = arm.poses;
  std::vector<Obbd> links;
  for (const auto& pose : poses) links.insert(links.end(), pose.begin(), pose.end());
  const std::string& links_source = arm.source;

  // Paper scale: SACT scenes.
  for (MpinetSceneKind kind : o.scenes) {
    w.scenes.push_back(SceneWorkload(kind, poses, o));
    const SactSceneWorkload& s = w.scenes.back();
    w.notes.push_back(std::string("SACT, ") + ToString(kind) + " scene (OctoMap, our boxes): " + s.Size() + "; " +
                      fmt::format("{} of {} queries collide; ", s.summary.collisions, s.summary.queries) +
                      links_source + " aimed across the scene and jittered, double precision, depth-first.");
  }

  // Paper scale: DeliBot runs.
  const std::string wean = o.data_dir + "/" + kWeanMap;
  const bool have_wean = std::filesystem::exists(wean);
  if (o.delibot_runs) {
    DelibotRunWorkload demo;
    demo.name = "demo";
    demo.grid = GenerateOfficeMap(OfficeMapOptions{});
    SimulationOptions sim;
    sim.record_count = kDemoRecords;
    demo.trace = SimulateTrace(demo.grid, sim).trace;
    w.runs.push_back(std::move(demo));
    const std::string log = o.data_dir + "/" + kRobotData1;
    if (have_wean && std::filesystem::exists(log)) {
      DelibotRunWorkload real;
      real.name = "robotdata1";
      real.grid = LoadCmuMap(wean);
      real.trace = ReadTrace(log, TraceReadOptions{});
      w.runs.push_back(std::move(real));
    } else {
      w.notes.push_back("DeliBot robotdata1: not run (no " + wean + " or " + log + ").");
    }
  }

  // Small batch: DeliBot's first update.
  w.ray_grid = have_wean ? LoadCmuMap(wean) : GenerateOfficeMap();
  w.first_update = UniformParticleBeams(w.ray_grid, o);
  w.notes.push_back(
      std::string("Small batch, DeliBot: ") +
      (have_wean ? "Wean map (" + wean + ")" : "generated office map (no " + wean + ")") +
      fmt::format(", {} x {} cells; one update of {} particles uniform in free space x {} beams, max range {:.3g} m, "
                  "beam-model leaf.",
                  w.ray_grid.size_x(), w.ray_grid.size_y(), o.particles, o.beams, o.max_range_m));

  // Small batch: SACT against the shelf's median-split tree, in float.
  const std::vector<Obbd>& obbs = links;
  const std::vector<Aabbd> scene = MakeShelfScene();
  const FlatBoxTree<float> tree(BuildMedianSplitTree(scene));
  std::vector<Obbf> obbs_f;
  for (const Obbd& b : obbs) obbs_f.push_back(b.Cast<float>());
  const CollisionBatch collisions = CollideBatch(tree, obbs_f, CollisionOptions<float>{});
  const CollisionSummary summary = Summarize(collisions);
  w.sact = SactKernelRecord(collisions);
  w.spheres = SphereKernelRecord(CollideSphereBatch(tree, obbs_f, 1, TraversalOrder::kDepthFirst).spheres);
  const SphereRobotReport spheres = CompareSphereRobot(tree, obbs_f, CollisionOptions<float>{}, 1);
  w.sphere_false_collisions = spheres.false_collisions;
  w.sphere_obb_collisions = spheres.obb_collisions;
  w.notes.push_back(
      std::string("Small batch, SACT: ") +
      (arm.from_file ? "mpnet_master robot-link OBBs (" + arm.path + ")"
                     : "seeded random workspace OBBs (no " + arm.path + ")") +
      fmt::format(", {} queries ({} collide), against the shelf scene ({} boxes, {}-node median-split tree, 32-byte "
                  "float nodes), depth-first; {:.2f} nodes per query.",
                  obbs.size(), summary.collisions, scene.size(), tree.nodes().size(), summary.nodes_per_query_mean));
  return w;
}

}  // namespace rc
