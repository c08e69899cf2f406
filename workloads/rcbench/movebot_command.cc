// `rcbench movebot`: OMPL's RRTstar for a LoCoBot-like 5-DoF arm among box
// obstacles (MoveBot), with the link-OBB collision checks (and, with a
// backend NN structure, the nearest-neighbour queries) recorded as kernel
// batches and priced on every modelled backend, one timeline row per batch
// of iterations. Every returned path is re-verified by an independent exact
// check (path_verification.h) before any output is written.
//
// Exit codes (also in --help): 0 an exact path, verified collision-free;
// 1 bad input (a file, or a start or goal in collision with the scene);
// 2 bad usage (also a start or goal outside the joint limits or in
// self-collision); 3 no exact path within the budget (approximate or none;
// every output is still written and says so); 4 a path that failed the
// independent check (a bug; nothing is written).
//
//   rcbench movebot                      # shared data's locobot scene, RoWild's start and goal
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include "backends/backend.h"
#include "backends/backend_params.h"
#include "backends/scheduler/scheduler_cli.h"
#include "common/atomic_file.h"
#include "common/exit_codes.h"
#include "common/input_error.h"
#include "robocore/collision/octree_from_octomap.h"
#include "workloads/movebot/movebot_report.h"
#include "workloads/movebot/path_verification.h"
#include "workloads/rcbench/commands.h"

namespace rc {
namespace {

constexpr int kExitNoExactPath = ToInt(ExitCode::kNoPath);
constexpr const char* kDefaultObstacles = "../shared/data/movebot/locobot_obs.txt";
// RoWild MoveBot's harness (cpu/src/locobot/harness.cpp): start and goal, rad.
constexpr ArmConfiguration kRowildStart = {-1.3962634, 0, 0, 0, 0};
constexpr ArmConfiguration kRowildGoal = {0, 1.04719755, -1.30899694, -1.30899694, 0};

struct MovebotCli {
  std::string obstacles_path, octree_path;
  std::vector<double> start, goal;
  std::uint64_t iterations = 0;
  double time_s = 0.0;
  std::string nn = "gnat";
  SchedulerCli scheduler;
  std::string timeline_path, anytime_path, ompl_log_path, path_path;
  double verify_resolution_rad = 0.0;
  bool no_self_collision = false;
  bool ompl_verbose = false;
  MoveBotSettings settings;
};

ArmConfiguration ToConfiguration(const std::vector<double>& v, const ArmConfiguration& fallback) {
  if (v.empty()) return fallback;
  ArmConfiguration q;
  for (int j = 0; j < kArmJoints; ++j) q[j] = v[j];
  return q;
}

// Seeds OMPL's process-wide generator. It takes effect only before the
// first RNG exists, so only the first call in a process counts; the runs
// themselves are seeded locally as well (movebot_rrtstar.h), so repeated
// runs in one process stay reproducible.
void SeedOmplOnce(std::uint32_t seed) {
  static bool seeded = false;
  if (seeded) return;
  ompl::RNG::setSeed(seed);
  seeded = true;
}

std::string Joined(const ArmConfiguration& q) {
  std::string s;
  for (int j = 0; j < kArmJoints; ++j) s += (j ? "," : "") + std::to_string(q[j]);
  return s;
}

int Run(MovebotCli& cli) {
  MoveBotSettings& s = cli.settings;
  SeedOmplOnce(s.seed);
  ompl::msg::setLogLevel(cli.ompl_verbose ? ompl::msg::LOG_INFO : ompl::msg::LOG_WARN);
  if (cli.iterations > 0 && cli.time_s > 0) throw UsageError("give --iterations N or --time S, not both");
  if (cli.iterations == 0 && cli.time_s <= 0) cli.iterations = 5000;
  s.iterations = cli.iterations;
  s.time_limit_s = cli.time_s;
  s.start = ToConfiguration(cli.start, kRowildStart);
  s.goal = ToConfiguration(cli.goal, kRowildGoal);
  s.nn = ParseNnKind(cli.nn);
  s.price_backends = !cli.scheduler.no_pricing;
  s.ledger = ToLedgerOptions(cli.scheduler);
  s.backend_params = BackendParametersOf(cli.scheduler);
  std::string error;
  if (!s.IsValid(&error)) throw UsageError(error);
  const double verify_resolution =
      cli.verify_resolution_rad > 0 ? cli.verify_resolution_rad : s.motion_resolution_rad / 10;
  if (!cli.octree_path.empty() && !cli.obstacles_path.empty())
    throw UsageError("give --obstacles FILE or --octree FILE.bt, not both");
  CheckOutputPaths({cli.timeline_path, cli.anytime_path, cli.path_path, cli.ompl_log_path});

  // The scene, and the same obstacles as world boxes for the independent check.
  ArmScene scene;
  std::vector<Obbd> check_boxes;
  std::string scene_text;
  std::string scene_path;  // the file the obstacles came from
  if (!cli.octree_path.empty()) {
    BoxTree tree = LoadOctoMapFile(cli.octree_path);
    for (const Aabbd& b : tree.boxes) {
      Obbd o;
      o.centre = b.centre;
      o.half = b.half;
      check_boxes.push_back(o);
    }
    scene = ArmScene::FromBoxTree(std::move(tree));
    scene_text = "octree " + cli.octree_path;
    scene_path = cli.octree_path;
  } else {
    const std::string path = cli.obstacles_path.empty() ? kDefaultObstacles : cli.obstacles_path;
    if (cli.obstacles_path.empty() && !std::filesystem::exists(path))
      throw InputError(path, 0, "", "the default obstacle file (shared data) is missing; give --obstacles FILE");
    const std::vector<Obstacle> obstacles = ReadObstacleFile(path);
    for (const Obstacle& o : obstacles) check_boxes.push_back(o.box);
    scene = ArmScene::FromObstacles(obstacles);
    scene_text = "obstacles " + path;
    scene_path = path;
  }
  std::cout << "scene: " << scene_text << " (" << scene.box_count() << " boxes in " << scene.frames().size()
            << " frame(s), " << scene.node_count() << " tree nodes)\n";
  std::cout << "arm: " << LocobotArmDescription().source << "; start " << Joined(s.start) << ", goal " << Joined(s.goal)
            << " rad\n";

  const LocobotArm arm;
  const SelfCollisionCheck self = cli.no_self_collision ? SelfCollisionCheck::kOff : SelfCollisionCheck::kOn;
  ArmCollisionChecker checker(arm, scene, {}, self);
  for (const auto& [q, option] : {std::pair{&s.start, "--start"}, std::pair{&s.goal, "--goal"}}) {
    std::string why;
    switch (CheckEndpoint(checker, *q, &why)) {
      case EndpointProblem::kNone: break;
      case EndpointProblem::kOutsideLimits:
      case EndpointProblem::kSelfCollision:
        throw UsageError(fmt::format("{} {:g} rad: {}", option, fmt::join(*q, ","), why));
      case EndpointProblem::kInCollision:
        throw InputError(scene_path, 0, "", fmt::format("{} {:g} rad is {}", option, fmt::join(*q, ","), why));
    }
  }
  const MoveBotResult result = RunMoveBot(checker, s);

  PathVerification verification;
  if (!result.path.empty()) {
    verification = VerifyPath(arm, check_boxes, result.path, verify_resolution, self);
    if (!verification.ok)
      throw std::runtime_error("the returned path failed the independent collision check: " + verification.message);
  }

  // Outputs only after the run and its check succeeded.
  if (!cli.timeline_path.empty()) WriteMoveBotTimeline(cli.timeline_path, result);
  if (!cli.anytime_path.empty()) WriteAnytimeCurve(cli.anytime_path, result);
  if (!cli.path_path.empty()) WriteArmPath(cli.path_path, result);
  if (!cli.ompl_log_path.empty()) {
    OmplLogContext context;
    context.setup = scene_text + "\nstart " + Joined(s.start) + "\ngoal " + Joined(s.goal) + "\nnn " + cli.nn +
                    "\nmotion resolution " + std::to_string(s.motion_resolution_rad) + " rad";
    context.seed = s.seed;
    context.time_limit_s = s.iterations > 0 ? result.planning_s : s.time_limit_s;
    context.verified = verification.ok && !result.path.empty();
    WriteOmplBenchmarkLog(cli.ompl_log_path, result, context);
  }
  PrintMoveBotSummary(std::cout, result, s);
  if (!result.path.empty())
    std::cout << "independent check       collision-free at " << verify_resolution
              << " rad: " << verification.configurations << " configurations, " << verification.exact_tests
              << " exact LP tests\n";
  for (const auto& [p, what] : {std::pair{&cli.timeline_path, "timeline"}, std::pair{&cli.anytime_path, "anytime"},
                                std::pair{&cli.path_path, "path"}, std::pair{&cli.ompl_log_path, "ompl log"}})
    if (!p->empty()) std::cout << std::left << std::setw(24) << what << *p << "\n";
  return result.status == MoveBotStatus::kExact ? 0 : kExitNoExactPath;
}

}  // namespace

void AddMovebotCommand(CLI::App& app) {
  auto cli = std::make_shared<MovebotCli>();
  MoveBotSettings& s = cli->settings;
  CLI::App* cmd = app.add_subcommand(
      "movebot",
      "OMPL RRTstar for a LoCoBot-like 5-DoF arm (MoveBot): link-OBB collision checks on the modelled "
      "backends, anytime cost timeline. With no options: the shared locobot scene and RoWild's start/goal.");
  cmd->add_option("--obstacles", cli->obstacles_path,
                  std::string("Obstacle file: roll,pitch,yaw,x,y,z,dimX,dimY,dimZ per line (rad, m, full sizes); "
                              "default ") +
                      kDefaultObstacles);
  cmd->add_option("--octree", cli->octree_path, "Scene as an OctoMap file (.bt or .ot): its occupied leaves");
  cmd->add_option("--start", cli->start, "Start q1,...,q5 (rad); default RoWild's -1.3962634,0,0,0,0")
      ->expected(kArmJoints)
      ->delimiter(',');
  cmd->add_option("--goal", cli->goal, "Goal q1,...,q5 (rad); default RoWild's 0,1.04719755,-1.30899694,-1.30899694,0")
      ->expected(kArmJoints)
      ->delimiter(',');
  cmd->add_option("--iterations", cli->iterations, "RRTstar iterations (count; default 5000 when --time is not given)");
  cmd->add_option("--time", cli->time_s, "Planning time budget (s), instead of --iterations (not repeatable)");
  cmd->add_option("--batch", s.batch_iterations, "Iterations per timeline row (count)")->capture_default_str();
  cmd->add_option("--resolution", s.motion_resolution_rad,
                  "Edge check spacing (rad, joint-space distance between checked configurations)")
      ->capture_default_str();
  cmd->add_option("--verify-resolution", cli->verify_resolution_rad,
                  "Spacing of the independent check of the returned path (rad); default resolution / 10");
  cmd->add_flag("--no-self-collision", cli->no_self_collision,
                "Do not test the arm's link boxes against each other (RoWild's problem); by default the upper arm is "
                "tested against the wrist and the hand, the forearm against the hand");
  cmd->add_option("--range", s.range_rad, "RRTstar's range (rad); 0: OMPL's default (0.2 x the space's extent)")
      ->capture_default_str();
  cmd->add_option("--goal-bias", s.goal_bias, "RRTstar's goal bias (probability)")->capture_default_str();
  cmd->add_option("--seed", s.seed, "Random seed (unitless, >= 1; OMPL ignores 0)")
      ->check(CLI::Range(1u, 4294967295u))
      ->capture_default_str();
  cmd->add_option("--nn", cli->nn, "Nearest-neighbour structure: gnat (OMPL's default) | p-ray | p-sphere")
      ->check(CLI::IsMember({"gnat", "p-ray", "p-sphere"}))
      ->capture_default_str();
  AddSchedulerOptions(*cmd, cli->scheduler, "nodes per query");
  cmd->add_option("--timeline", cli->timeline_path, "Timeline CSV, one row per batch of iterations");
  cmd->add_option("--anytime", cli->anytime_path, "Anytime curve CSV: time_s, iterations, best_cost_rad");
  cmd->add_option("--ompl-log", cli->ompl_log_path, "OMPL benchmark log (ompl_benchmark_statistics.py, Planner Arena)");
  cmd->add_option("--path", cli->path_path, "Path CSV: one configuration per line, q1_rad..q5_rad");
  cmd->add_flag("--ompl-verbose", cli->ompl_verbose, "Show OMPL's own info messages");
  cmd->footer(ExitCodeFooter(
      "no exact path within the budget (approximate or none; outputs are still written). A start or goal outside "
      "[-pi/2, pi/2] or in self-collision counts as a bad command line, one in collision with the scene as bad "
      "input, and a returned "
      "path that fails the independent collision check as an internal error, with nothing written"));
  cmd->callback([cli] { ExitUnlessSuccess(Run(*cli)); });
}

}  // namespace rc
