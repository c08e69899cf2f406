// `rcbench collide`: robot-link OBBs against a scene of axis-aligned boxes
// (a box list, an OctoMap, or the generated shelf), one query per OBB, with
// the staged SACT at every visited node of the scene tree. Writes one row
// per OBB and a timeline of what the queries did (nodes per query, how the
// node tests ended), and prints the sphere-robot and artifact comparisons.
//
// The OBB batch runs through the RoboCore API (RoboCoreContext::
// CheckCollisions with the shipped SACT program); the sphere robot
// (--spheres-per-obb spheres covering each OBB) runs the same tree with
// programs/sphere_aabb.asm. Both records are priced on every modelled
// backend; --robot-model picks whose answers go to --output.
//
// Output exit_axis: how the query's last node test ended: 0..14 the SACT
// axis that separated (sact.h numbering; a collision-free query), -1
// overlap (the colliding leaf), -2 a sphere pre-test rejected (or, with
// --robot-model spheres, the OBB's last sphere missed its last node), -3 no
// node was tested (empty scene).
//
//   rcbench collide --obbs ../shared/data/collision/mpnet_master_obb.csv --scene shelf
#include <filesystem>
#include <iomanip>
#include <iostream>

#include "backends/backend.h"
#include "backends/backend_params.h"
#include "backends/backend_preset.h"
#include "common/atomic_file.h"
#include "common/exit_codes.h"
#include "common/input_error.h"
#include "robocore/collision/box_csv.h"
#include "robocore/collision/collision_summary.h"
#include "robocore/collision/octree_from_octomap.h"
#include "robocore/collision/sact_kernel_record.h"
#include "robocore/collision/shelf_scene.h"
#include "robocore/collision/sphere_robot.h"
#include "robocore/robocore_api.h"
#include "robocore/shipped_programs.h"
#include "traces/csv_table.h"
#include "workloads/rcbench/commands.h"

namespace rc {
namespace {

// The artifact's octree node (REFERENCE.md section 2), for comparison.
constexpr int kArtifactNodeBytes = 432;

struct CollideCli {
  std::string obbs_path, boxes_path, octree_path, scene;
  std::string output_path, timeline_path, scene_output_path, backend_params_path;
  std::string precision = "double", traversal = "dfs", robot_model = "obb", backend = "robocore";
  int spheres_per_obb = 1;
  double parallel_epsilon = 1e-6;
  bool sphere_pretest = false;
  ShelfSceneOptions shelf;
};

std::string ExitName(int exit) { return exit == kNoNodeTested ? "none" : SactAxisName(exit); }

void WriteOutput(const std::string& path, const std::vector<CollisionResult>& results) {
  CsvTable table(path, {"index", "collides", "nodes_visited", "exit_axis"});
  for (std::size_t i = 0; i < results.size(); ++i) {
    const CollisionResult& q = results[i];
    table.AddRow({i, q.collides ? 1 : 0, q.nodes_visited, int{q.exit_axis}});
  }
  table.Commit();
}

// The sphere robot's answer per OBB: collides if any of its spheres does;
// nodes summed over its spheres; the exit of its last sphere's last test.
std::vector<CollisionResult> SphereResults(const SphereRobotBatch& spheres) {
  std::vector<CollisionResult> results(spheres.obb_collides.size());
  const auto n = static_cast<std::size_t>(spheres.spheres_per_obb);
  for (std::size_t k = 0; k < results.size(); ++k) {
    results[k].collides = spheres.obb_collides[k];
    for (std::size_t s = k * n; s < (k + 1) * n; ++s) {
      const TraversalOutcome& q = spheres.spheres.outcomes[s];
      results[k].nodes_visited += q.nodes_visited;
      results[k].exit_axis = q.last_exit;
      if (q.collides) {
        results[k].colliding_box = q.colliding_box;
        break;
      }
    }
  }
  return results;
}

// Long format (section, key, value): one file for the summary numbers, the
// nodes-per-query histogram and both exit-axis distributions.
// Every modelled backend prices the batch's recorded traversal (run once,
// price many times). Empty for an empty batch.
std::vector<BatchCost> PriceOnEveryBackend(const KernelRecord& record, const BackendParameters& params) {
  if (record.query_count() == 0) return {};
  std::vector<std::unique_ptr<Backend>> owned;
  std::vector<const Backend*> backends;
  for (const std::string& name : Backend::ModelledNames()) {
    owned.push_back(Backend::Create(name, params));
    backends.push_back(owned.back().get());
  }
  return PriceAll(backends, record);
}

void WriteTimeline(const std::string& path, const CollisionSummary& s, const CollisionBatch& batch,
                   const std::vector<BatchCost>& costs, const SphereRobotReport& spheres,
                   const std::vector<BatchCost>& sphere_costs, const std::string& backend) {
  CsvTableOptions options;
  options.significant_digits = 10;
  CsvTable table(path, {"section", "key", "value"}, options);
  auto add = [&table](const char* section, const std::string& key, CsvCell value) {
    table.AddRow({section, key, std::move(value)});
  };
  add("summary", "backend", backend);
  add("summary", "queries", s.queries);
  add("summary", "collisions", s.collisions);
  add("summary", "node_visits", s.node_visits);
  add("summary", "nodes_per_query_mean", s.nodes_per_query_mean);
  add("summary", "nodes_per_query_max", s.nodes_max);
  add("summary", "tree_nodes", batch.node_count);
  add("summary", "node_bytes", batch.node_bytes);
  for (const NodesHistogramBin& b : s.nodes_histogram)
    add("nodes_per_query_histogram", std::to_string(b.lo) + '-' + std::to_string(b.hi), b.queries);
  for (int slot = 0; slot < kExitSlots; ++slot)
    add("node_test_exit", ExitName(ExitOfSlot(slot)), s.node_test_exits[slot]);
  for (int slot = 0; slot < kExitSlots; ++slot)
    add("query_last_exit", ExitName(ExitOfSlot(slot)), s.query_last_exits[slot]);
  add("stages", "sphere_pretest", s.sphere_pretests);
  add("stages", "pre_process", s.pre_process);
  add("stages", "box_normal", s.box_normal);
  add("stages", "edge_edge", s.edge_edge);
  add("stages", "sphere_decided", s.sphere_decided);
  for (const BatchCost& c : costs) {
    add("cycles", c.backend, c.cycles);
    add("energy_j", c.backend, c.energy_joules);
  }
  add("sphere_robot", "spheres_per_obb", spheres.spheres_per_obb);
  add("sphere_robot", "collisions", spheres.sphere_collisions);
  add("sphere_robot", "false_collisions", spheres.false_collisions);
  add("sphere_robot", "false_collision_rate", spheres.false_collision_rate());
  add("sphere_robot", "missed_collisions", spheres.missed_collisions);
  add("sphere_robot", "node_visits", spheres.sphere_nodes);
  for (const BatchCost& c : sphere_costs) {
    add("cycles_spheres", c.backend, c.cycles);
    add("energy_j_spheres", c.backend, c.energy_joules);
  }
  table.Commit();
}

// `ran` marks the backend that ran the batch (--backend).
void PrintCosts(std::ostream& out, const std::vector<BatchCost>& costs, const std::string& ran) {
  for (const BatchCost& c : costs)
    out << (c.backend == ran ? "* " : "  ") << std::left << std::setw(12) << c.backend << std::right << std::setw(10)
        << c.cycles << " cycles  " << std::setprecision(4) << 1e6 * c.seconds << " us  " << 1e6 * c.energy_joules
        << " uJ\n";
}

void PrintSummary(std::ostream& out, const CollisionSummary& s) {
  out << "queries                 " << s.queries << "\ncollisions              " << s.collisions
      << "\nnodes per query         mean " << std::setprecision(4) << s.nodes_per_query_mean << ", max " << s.nodes_max
      << "\nnodes per query histogram\n";
  for (const NodesHistogramBin& b : s.nodes_histogram)
    if (b.queries) out << "  " << std::setw(5) << b.lo << " - " << std::setw(5) << b.hi << "  " << b.queries << '\n';
  out << "node tests by exit (all visits)\n";
  for (int slot = 0; slot < kExitSlots; ++slot)
    if (s.node_test_exits[slot])
      out << "  " << std::setw(8) << ExitName(ExitOfSlot(slot)) << "  " << s.node_test_exits[slot] << '\n';
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

  const BackendParameters params =
      cli.backend_params_path.empty() ? BackendParameters{} : LoadBackendPreset(cli.backend_params_path).backend;
  // Each kernel runs once (a scene builds only what it needs): the OBB
  // batch through the RoboCore API, which also hands back its visits for
  // the summary, or, with sphere pre-tests (which the SACT program cannot
  // price), directly and unpriced; the sphere robot; and the artifact's
  // convention below, answers only. Only with sphere pre-tests does the
  // plain SACT run a second time, answers only, for the sphere comparison.
  std::vector<CollisionResult> results;
  KernelRecord record;
  std::vector<BatchCost> costs;
  CollisionBatch batch;
  if (!options.sact.sphere_pretests) {
    RoboCoreContext robocore;
    robocore.ConfigRoboCore(ShippedStepProgram(StepProgramKind::kSactTest));
    robocore.ConfigDecode({{FetchKind::kTreeNode, flat.node_bytes()}});
    robocore.CheckCollisions(obbs, flat, results, record, options, &batch);
    costs = PriceOnEveryBackend(record, params);
  } else {
    batch = CollideBatch(flat, obbs, options);
    for (const TraversalOutcome& q : batch.outcomes) results.push_back(ResultOf(q));
  }
  const CollisionSummary summary = Summarize(batch);
  const SphereRobotBatch sphere_batch = CollideSphereBatch(flat, obbs, cli.spheres_per_obb, options.order);
  const std::vector<BatchCost> sphere_costs = PriceOnEveryBackend(SphereKernelRecord(sphere_batch.spheres), params);
  // The sphere robot is compared with the exact SACT: the batch above, or
  // with sphere pre-tests the SACT alone, answers only.
  std::vector<TraversalOutcome> exact;
  if (options.sact.sphere_pretests) {
    CollisionOptions<Scalar> exact_options = options;
    exact_options.sact.sphere_pretests = false;
    exact = CollideAnswers(flat, obbs, exact_options);
  }
  const SphereRobotReport spheres =
      CompareSphereRobot(sphere_batch, options.sact.sphere_pretests ? exact : batch.outcomes);
  // Outputs only after the whole run succeeded.
  if (!cli.output_path.empty())
    WriteOutput(cli.output_path, cli.robot_model == "spheres" ? SphereResults(sphere_batch) : results);
  if (!cli.timeline_path.empty())
    WriteTimeline(cli.timeline_path, summary, batch, costs, spheres, sphere_costs, cli.backend);

  std::cout << "scene: " << ToString(tree.kind) << ", " << tree.boxes.size() << " boxes, " << flat.nodes().size()
            << " nodes of " << flat.node_bytes() << " B (" << flat.bytes() << " B; the artifact's node is "
            << kArtifactNodeBytes << " B), height " << tree.height() << "\n";
  std::cout << "kernel: " << cli.precision << " SACT, epsilon " << cli.parallel_epsilon << ", "
            << (cli.sphere_pretest ? "sphere pre-tests, " : "") << ToString(options.order) << " traversal\n";
  PrintSummary(std::cout, summary);
  std::cout << "backend                 " << cli.backend
            << (cli.backend == "cpu" ? " (the host reference: no cost model)" : " (marked *)") << '\n';
  if (options.sact.sphere_pretests) {
    std::cout << "backend pricing         skipped: sphere pre-tests have no section in the SACT program\n";
  } else {
    std::cout << "modelled cost of the batch (every backend prices the same traversal):\n";
    PrintCosts(std::cout, costs, cli.backend);
  }

  std::cout << "sphere robot            " << cli.spheres_per_obb << " sphere(s) per OBB: " << spheres.sphere_collisions
            << " collisions, " << spheres.false_collisions << " false (" << std::setprecision(3)
            << 100 * spheres.false_collision_rate() << "% of queries, " << 100 * spheres.false_rate_among_free()
            << "% of collision-free ones), " << spheres.missed_collisions << " missed; nodes " << spheres.sphere_nodes
            << " vs " << spheres.obb_nodes << " for OBBs\n";
  if (!sphere_costs.empty()) {
    std::cout << "modelled cost of the sphere robot (programs/sphere_aabb.asm, same tree):\n";
    PrintCosts(std::cout, sphere_costs, cli.backend);
  }
  CollisionOptions<Scalar> artifact = options;
  artifact.sact.convention = TranslationConvention::kArtifactRows;
  artifact.sact.sphere_pretests = false;
  const std::vector<TraversalOutcome> wrong = CollideAnswers(flat, obbs, artifact);
  std::size_t differ = 0;
  for (std::size_t i = 0; i < obbs.size(); ++i) differ += wrong[i].collides != batch.outcomes[i].collides;
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
  CheckOutputPaths({cli.output_path, cli.timeline_path, cli.scene_output_path});
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
      "collide",
      "Robot-link OBBs against a scene of boxes: staged 15-axis SACT over the scene tree, one query per OBB");
  cmd->add_option("--obbs", cli->obbs_path,
                  "OBB CSV in the mpnet_master format (pose, joint, centre, 3 axes, half-lengths; m)")
      ->required();
  cmd->add_option("--boxes", cli->boxes_path, "Scene boxes CSV, one 'cx,cy,cz,hx,hy,hz' per line (m), optional header");
  cmd->add_option("--octree", cli->octree_path,
                  "Scene as an OctoMap file (.bt or .ot); its occupied leaves are the boxes");
  cmd->add_option("--scene", cli->scene, "Generated scene: shelf (a cubby shelf in front of the robot and one behind)");
  cmd->add_option("--scene-seed", cli->shelf.seed, "Seed of the shelf's objects (unitless)")->capture_default_str();
  cmd->add_option("--scene-output", cli->scene_output_path, "Write the generated scene's boxes here (box CSV)");
  cmd->add_option("--output", cli->output_path,
                  "Per-OBB results CSV: index,collides,nodes_visited,exit_axis (exit of the last node test: "
                  "0..14 separating axis, -1 overlap, -2 sphere reject, -3 none)");
  cmd->add_option("--backend-params", cli->backend_params_path,
                  "A named preset (artifact) or a JSON file overriding backend cost parameters (see rcbench "
                  "backends)");
  cmd->add_option(
      "--timeline", cli->timeline_path,
      "Batch timeline CSV (section,key,value): nodes per query mean and histogram, exit-axis distributions");
  cmd->add_option("--precision", cli->precision, "SACT and node precision: double | float")
      ->check(CLI::IsMember({"double", "float"}))
      ->capture_default_str();
  cmd->add_option("--traversal", cli->traversal, "dfs (depth-first) | bfs (breadth-first, as the artifact)")
      ->check(CLI::IsMember({"dfs", "bfs"}))
      ->capture_default_str();
  cmd->add_option("--epsilon", cli->parallel_epsilon, "Added to |R_ij| against near-parallel edges (unitless)")
      ->capture_default_str();
  cmd->add_option("--backend", cli->backend,
                  "The backend that runs the batch (marked * and named in the timeline); every backend gives the "
                  "same answers and every modelled one prices the batch: cpu | simt | ttaplus | ttaplus-p | "
                  "ttaplus-cr | robocore")
      ->check(CLI::IsMember(Backend::Names()))
      ->capture_default_str();
  cmd->add_option("--robot-model", cli->robot_model,
                  "Whose answers --output gets: obb (the exact SACT) | spheres (the sphere robot, "
                  "--spheres-per-obb spheres covering each OBB); both are always priced and compared")
      ->check(CLI::IsMember({"obb", "spheres"}))
      ->capture_default_str();
  cmd->add_option("--spheres-per-obb", cli->spheres_per_obb,
                  "Spheres covering each OBB in the sphere robot (count; 1 = the bounding sphere, n = n slabs "
                  "along the longest axis)")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  cmd->add_flag("--sphere-pretest", cli->sphere_pretest,
                "Bounding-sphere reject and inscribed-sphere accept before the SACT axes");
  cmd->footer(ExitCodeFooter(""));
  cmd->callback([cli] { Run(*cli); });
}

}  // namespace rc
