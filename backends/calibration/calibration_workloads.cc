#include "backends/calibration/calibration_workloads.h"

#include <cstdio>
#include <filesystem>

#include <Eigen/Geometry>

#include "backends/calibration/sact_kernel_record.h"
#include "common/angles.h"
#include "common/input_error.h"
#include "common/random_stream.h"
#include "maps/cmu_map_loader.h"
#include "maps/office_map_generator.h"
#include "robocore/collision/box_csv.h"
#include "robocore/collision/collision_summary.h"
#include "robocore/collision/shelf_scene.h"
#include "robocore/collision/sphere_robot.h"
#include "robocore/ray_batch_recorded.h"

namespace rc {
namespace {

const char* const kWeanMap = "wean/wean.dat";
const char* const kRobotObbs = "collision/mpnet_master_obb.csv";

std::string Format(const char* format, double a, double b = 0, double c = 0, double d = 0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, format, a, b, c, d);
  return buf;
}

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

}  // namespace

bool CalibrationOptions::IsValid(std::string* error) const {
  auto fail = [&](const char* what) {
    if (error) *error = what;
    return false;
  };
  if (particles < 1 || beams < 1) return fail("calibration: particles and beams must be >= 1");
  if (!(max_range_m > 0)) return fail("calibration: max range must be > 0");
  if (random_obbs < 1) return fail("calibration: random OBB count must be >= 1");
  return true;
}

CalibrationWorkloads MakeCalibrationWorkloads(const CalibrationOptions& o) {
  std::string error;
  if (!o.IsValid(&error)) throw UsageError(error);
  CalibrationWorkloads w;

  const std::string wean = o.data_dir + "/" + kWeanMap;
  const bool have_wean = std::filesystem::exists(wean);
  const OccupancyGrid grid = have_wean ? LoadCmuMap(wean) : GenerateOfficeMap();
  const RayBatch batch = UniformParticleBeams(grid, o);
  std::vector<RayHit> hits;
  std::string nodes;
  for (RayCastMethod method : {RayCastMethod::kMarch, RayCastMethod::kDda, RayCastMethod::kRayMarching}) {
    const RayCastScene scene(grid, method);
    RayCasterRecord r;
    r.method = method;
    CastRayBatchRecorded(scene, batch, hits, r.record);
    nodes += std::string(nodes.empty() ? "" : ", ") + ToString(method) +
             Format(" %.1f", double(r.record.total_nodes()) / double(r.record.query_count()));
    w.rays.push_back(std::move(r));
  }
  w.ray_description =
      std::string("DeliBot: ") + (have_wean ? "Wean map (" + wean + ")" : "generated office map (no " + wean + ")") +
      Format(", %.0f x %.0f cells; %.0f particles uniform in free space x %.0f beams", grid.size_x(), grid.size_y(),
             o.particles, o.beams) +
      Format(", max range %.3g m, beam-model leaf; nodes per ray: ", o.max_range_m) + nodes + ".";

  const std::string robot_path = o.data_dir + "/" + kRobotObbs;
  const bool have_robot = std::filesystem::exists(robot_path);
  std::vector<Obbd> obbs;
  if (have_robot)
    for (const RobotObb& r : ReadObbCsv(robot_path)) obbs.push_back(r.obb);
  else
    obbs = RandomWorkspaceObbs(o);
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
  w.collision_description =
      std::string("SACT: ") +
      (have_robot ? "mpnet_master robot-link OBBs (" + robot_path + ")"
                  : "seeded random workspace OBBs (no " + robot_path + ")") +
      Format(", %.0f queries (%.0f collide), against the shelf scene (%.0f boxes, ", double(obbs.size()),
             double(summary.collisions), double(scene.size())) +
      Format("%.0f-node median-split tree, 32-byte float nodes), depth-first; %.2f nodes per query, %.1f axis "
             "tests per node on average.",
             double(tree.nodes().size()), summary.nodes_per_query_mean,
             double(summary.box_normal + summary.edge_edge) / double(summary.node_visits));
  return w;
}

}  // namespace rc
