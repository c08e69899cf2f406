// `rcbench collide`: robot-link OBBs against a scene of axis-aligned boxes
// (a box list, an OctoMap, or the generated shelf), one query per OBB, with
// the staged SACT at every visited node of the scene tree. Writes one row
// per OBB and a timeline of what the queries did (nodes per query, how the
// node tests ended), and prints the sphere-robot and artifact comparisons.
//
// Output exit_axis: how the query's last node test ended: 0..14 the SACT
// axis that separated (sact.h numbering; a collision-free query), -1
// overlap (the colliding leaf), -2 a sphere pre-test rejected, -3 no node
// was tested (empty scene).
//
//   rcbench collide --obbs ../shared/data/collision/mpnet_master_obb.csv --scene shelf
#include <filesystem>
#include <iomanip>
#include <iostream>

#include "backends/backend.h"
#include "backends/backend_params.h"
#include "backends/calibration/sact_kernel_record.h"
#include "common/atomic_file.h"
#include "common/input_error.h"
#include "robocore/collision/box_csv.h"
#include "robocore/collision/collision_summary.h"
#include "robocore/collision/octree_from_octomap.h"
#include "robocore/collision/shelf_scene.h"
#include "robocore/collision/sphere_robot.h"
#include "workloads/rcbench/commands.h"

namespace rc {
namespace {

// The artifact's octree node (REFERENCE.md section 2), for comparison.
constexpr int kArtifactNodeBytes = 432;

struct CollideCli {
  std::string obbs_path, boxes_path, octree_path, scene;
  std::string output_path, timeline_path, scene_output_path, backend_params_path;
  std::string precision = "double", traversal = "dfs";
  double parallel_epsilon = 1e-6;
  bool sphere_pretest = false;
  ShelfSceneOptions shelf;
};

std::string ExitName(int exit) {
  return exit == kNoNodeTested ? "none" : SactAxisName(exit);
}

void CreateParent(const std::string& path) {
  const auto parent = std::filesystem::path(path).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
}

void WriteOutput(const std::string& path, const CollisionBatch& batch) {
  CreateParent(path);
  AtomicFile file(path);
  std::ostream& out = file.stream();
  out << "index,collides,nodes_visited,exit_axis\n";
  for (std::size_t i = 0; i < batch.query_count(); ++i) {
    const TraversalOutcome& q = batch.outcomes[i];
    out << i << ',' << (q.collides ? 1 : 0) << ',' << q.nodes_visited << ',' << int{q.last_exit} << '\n';
  }
  file.Commit();
}

// Long format (section, key, value): one file for the summary numbers, the
// nodes-per-query histogram and both exit-axis distributions.
// Every modelled backend prices the batch's recorded traversal (run once,
// price many times). Empty when sphere pre-tests decided some visits: the
// shipped SACT program has no sphere section to price them with.
std::vector<BatchCost> PriceCollisionBatch(const CollisionBatch& batch, const BackendParameters& params) {
  if (batch.outcomes.empty()) return {};
  KernelRecord record;
  try {
    record = SactKernelRecord(batch);
  } catch (const std::invalid_argument&) {
    return {};
  }
  std::vector<std::unique_ptr<Backend>> owned;
  std::vector<const Backend*> backends;
  for (const std::string& name : Backend::ModelledNames()) {
    owned.push_back(Backend::Create(name, params));
    backends.push_back(owned.back().get());
  }
  return PriceAll(backends, record);
}

void WriteTimeline(const std::string& path, const CollisionSummary& s, const CollisionBatch& batch,
                   const std::vector<BatchCost>& costs) {
  CreateParent(path);
  AtomicFile file(path);
  std::ostream& out = file.stream();
  out << "section,key,value\n" << std::setprecision(10);
  out << "summary,queries," << s.queries << "\nsummary,collisions," << s.collisions
      << "\nsummary,node_visits," << s.node_visits << "\nsummary,nodes_per_query_mean," << s.nodes_per_query_mean
      << "\nsummary,nodes_per_query_max," << s.nodes_max << "\nsummary,tree_nodes," << batch.node_count
      << "\nsummary,node_bytes," << batch.node_bytes << "\n";
  for (const NodesHistogramBin& b : s.nodes_histogram)
    out << "nodes_per_query_histogram," << b.lo << '-' << b.hi << ',' << b.queries << '\n';
  for (int slot = 0; slot < kExitSlots; ++slot)
    out << "node_test_exit," << ExitName(ExitOfSlot(slot)) << ',' << s.node_test_exits[slot] << '\n';
  for (int slot = 0; slot < kExitSlots; ++slot)
    out << "query_last_exit," << ExitName(ExitOfSlot(slot)) << ',' << s.query_last_exits[slot] << '\n';
  out << "stages,sphere_pretest," << s.sphere_pretests << "\nstages,pre_process," << s.pre_process
      << "\nstages,box_normal," << s.box_normal << "\nstages,edge_edge," << s.edge_edge
      << "\nstages,sphere_decided," << s.sphere_decided << '\n';
  for (const BatchCost& c : costs)
    out << "cycles," << c.backend << ',' << c.cycles << "\nenergy_j," << c.backend << ',' << c.energy_joules << '\n';
  file.Commit();
}

void PrintSummary(std::ostream& out, const CollisionSummary& s) {
  out << "queries                 " << s.queries << "\ncollisions              " << s.collisions
      << "\nnodes per query         mean " << std::setprecision(4) << s.nodes_per_query_mean << ", max "
      << s.nodes_max << "\nnodes per query histogram\n";
  for (const NodesHistogramBin& b : s.nodes_histogram)
    if (b.queries) out << "  " << std::setw(5) << b.lo << " - " << std::setw(5) << b.hi << "  " << b.queries << '\n';
  out << "node tests by exit (all visits)\n";
  for (int slot = 0; slot < kExitSlots; ++slot)
    if (s.node_test_exits[slot]) out << "  " << std::setw(8) << ExitName(ExitOfSlot(slot)) << "  " << s.node_test_exits[slot] << '\n';
  out << "SACT stages             PRE " << s.pre_process << ", BOX " << s.box_normal << ", EDGE " << s.edge_edge;
  if (s.sphere_pretests) out << ", sphere pre-tests " << s.sphere_pretests << " (" << s.sphere_decided << " decided)";
  out << '\n';
}

template <typename Scalar>
void RunCollide(const CollideCli& cli, const BoxTree& tree, const std::vector<RobotObb>& robot) {
  const FlatBoxTree<Scalar> flat(tree);
  std::vector<Obb<Scalar>> obbs;
  obbs.reserve(robot.size());
  for (const RobotObb& r : robot) obbs.push_back(r.obb.template Cast<Scalar>());
  CollisionOptions<Scalar> options;
  options.sact.parallel_epsilon = static_cast<Scalar>(cli.parallel_epsilon);
  options.sact.sphere_pretests = cli.sphere_pretest;
  options.order = ParseTraversalOrder(cli.traversal);
  std::string error;
  if (!options.sact.IsValid(&error)) throw UsageError(error);

  const CollisionBatch batch = CollideBatch(flat, obbs, options);
  const CollisionSummary summary = Summarize(batch);
  const BackendParameters params =
      cli.backend_params_path.empty() ? BackendParameters{} : LoadBackendParameters(cli.backend_params_path);
  const std::vector<BatchCost> costs = PriceCollisionBatch(batch, params);
  // Outputs only after the whole run succeeded.
  if (!cli.output_path.empty()) WriteOutput(cli.output_path, batch);
  if (!cli.timeline_path.empty()) WriteTimeline(cli.timeline_path, summary, batch, costs);

  std::cout << "scene: " << ToString(tree.kind) << ", " << tree.boxes.size() << " boxes, " << flat.nodes().size()
            << " nodes of " << flat.node_bytes() << " B (" << flat.bytes() << " B; the artifact's node is "
            << kArtifactNodeBytes << " B), height " << tree.height() << "\n";
  std::cout << "kernel: " << cli.precision << " SACT, epsilon " << cli.parallel_epsilon << ", "
            << (cli.sphere_pretest ? "sphere pre-tests, " : "") << ToString(options.order) << " traversal\n";
  PrintSummary(std::cout, summary);
  if (costs.empty()) {
    std::cout << "backend pricing         skipped: sphere pre-tests have no section in the SACT program\n";
  } else {
    std::cout << "modelled cost of the batch (every backend prices the same traversal):\n";
    for (const BatchCost& c : costs)
      std::cout << "  " << std::left << std::setw(12) << c.backend << std::right << std::setw(10) << c.cycles
                << " cycles  " << std::setprecision(4) << 1e6 * c.seconds << " us  " << 1e6 * c.energy_joules
                << " uJ\n";
  }

  const SphereRobotReport spheres = CompareSphereRobot(flat, obbs, options);
  std::cout << "sphere robot            " << spheres.sphere_collisions << " collisions, " << spheres.false_collisions
            << " false (" << std::setprecision(3) << 100 * spheres.false_collision_rate() << "% of queries, "
            << 100 * spheres.false_rate_among_free() << "% of collision-free ones), " << spheres.missed_collisions
            << " missed; nodes " << spheres.sphere_nodes << " vs " << spheres.obb_nodes << " for OBBs\n";
  CollisionOptions<Scalar> artifact = options;
  artifact.sact.convention = TranslationConvention::kArtifactRows;
  artifact.sact.sphere_pretests = false;
  const CollisionBatch wrong = CollideBatch(flat, obbs, artifact);
  std::size_t differ = 0;
  for (std::size_t i = 0; i < obbs.size(); ++i) differ += wrong.outcomes[i].collides != batch.outcomes[i].collides;
  std::cout << "artifact SACT convention (translation on axis rows): " << differ << " of " << obbs.size()
            << " answers differ\n";
  if (!cli.output_path.empty()) std::cout << "output                  " << cli.output_path << "\n";
  if (!cli.timeline_path.empty()) std::cout << "timeline                " << cli.timeline_path << "\n";
}

void Run(const CollideCli& cli) {
  const int scenes = !cli.boxes_path.empty() + !cli.octree_path.empty() + !cli.scene.empty();
  if (scenes != 1) throw UsageError("give exactly one scene: --boxes FILE.csv, --octree FILE.bt|.ot or --scene shelf");
  if (!cli.scene.empty() && cli.scene != "shelf") throw UsageError("--scene: only 'shelf' is generated");
  if (!cli.scene_output_path.empty() && cli.scene.empty()) throw UsageError("--scene-output needs --scene");
  const std::vector<RobotObb> robot = ReadObbCsv(cli.obbs_path);
  std::cout << "obbs: " << cli.obbs_path << " (" << robot.size() << " OBBs)\n";

  BoxTree tree;
  if (!cli.boxes_path.empty()) {
    std::vector<Aabbd> boxes = ReadBoxCsv(cli.boxes_path);
    tree = BuildMedianSplitTree(std::move(boxes));
  } else if (!cli.octree_path.empty()) {
    tree = LoadOctoMapFile(cli.octree_path);
  } else {
    std::string error;
    if (!cli.shelf.IsValid(&error)) throw UsageError("shelf scene: " + error);
    std::vector<Aabbd> boxes = MakeShelfScene(cli.shelf);
    if (!cli.scene_output_path.empty()) {
      CreateParent(cli.scene_output_path);
      AtomicFile file(cli.scene_output_path);
      WriteBoxCsv(file.stream(), boxes);
      file.Commit();
      std::cout << "scene boxes written to  " << cli.scene_output_path << "\n";
    }
    tree = BuildMedianSplitTree(std::move(boxes));
  }
  if (cli.precision == "float")
    RunCollide<float>(cli, tree, robot);
  else
    RunCollide<double>(cli, tree, robot);
}

}  // namespace

void AddCollideCommand(CLI::App& app) {
  auto cli = std::make_shared<CollideCli>();
  CLI::App* cmd = app.add_subcommand(
      "collide", "Robot-link OBBs against a scene of boxes: staged 15-axis SACT over the scene tree, one query per OBB");
  cmd->add_option("--obbs", cli->obbs_path, "OBB CSV in the mpnet_master format (pose, joint, centre, 3 axes, half-lengths; m)")
      ->required();
  cmd->add_option("--boxes", cli->boxes_path, "Scene boxes CSV, one 'cx,cy,cz,hx,hy,hz' per line (m), optional header");
  cmd->add_option("--octree", cli->octree_path, "Scene as an OctoMap file (.bt or .ot); its occupied leaves are the boxes");
  cmd->add_option("--scene", cli->scene, "Generated scene: shelf (a cubby shelf in front of the robot and one behind)");
  cmd->add_option("--scene-seed", cli->shelf.seed, "Seed of the shelf's objects (unitless)")->capture_default_str();
  cmd->add_option("--scene-output", cli->scene_output_path, "Write the generated scene's boxes here (box CSV)");
  cmd->add_option("--output", cli->output_path,
                  "Per-OBB results CSV: index,collides,nodes_visited,exit_axis (exit of the last node test: "
                  "0..14 separating axis, -1 overlap, -2 sphere reject, -3 none)");
  cmd->add_option("--backend-params", cli->backend_params_path,
                  "JSON file overriding backend cost parameters (see rcbench backends)");
  cmd->add_option("--timeline", cli->timeline_path,
                  "Batch timeline CSV (section,key,value): nodes per query mean and histogram, exit-axis distributions");
  cmd->add_option("--precision", cli->precision, "SACT and node precision: double | float")
      ->check(CLI::IsMember({"double", "float"}))
      ->capture_default_str();
  cmd->add_option("--traversal", cli->traversal, "dfs (depth-first) | bfs (breadth-first, as the artifact)")
      ->check(CLI::IsMember({"dfs", "bfs"}))
      ->capture_default_str();
  cmd->add_option("--epsilon", cli->parallel_epsilon, "Added to |R_ij| against near-parallel edges (unitless)")
      ->capture_default_str();
  cmd->add_flag("--sphere-pretest", cli->sphere_pretest,
                "Bounding-sphere reject and inscribed-sphere accept before the SACT axes");
  cmd->callback([cli] { Run(*cli); });
}

}  // namespace rc
