// `rcbench carribot`: grid A* / weighted A* for a point robot or a rectangular
// footprint (CarriBot), on MovingAI scenarios or one start/goal pair. A
// footprint's collision checks run on the collision kernel (OBB against the
// map's quadtree), and every launch is priced on every modelled backend while
// the --backend policy picks the one that ran (carribot_run.h).
//
// Exit codes (also in --help): 0 every query found a path; 1 bad input;
// 2 bad usage; 3 at least one query found no path. Code 3 is reached through
// ExitUnlessSuccess (common/exit_codes.h) after every output is written,
// because main() maps every exception to 1 or 2.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include <CLI/CLI.hpp>

#include "backends/backend.h"
#include "backends/backend_params.h"
#include "backends/scheduler/scheduler_cli.h"
#include "common/atomic_file.h"
#include "common/exit_codes.h"
#include "common/input_error.h"
#include "maps/map_loader.h"
#include "traces/csv_table.h"
#include "workloads/carribot/carribot_report.h"
#include "workloads/carribot/carribot_run.h"
#include "workloads/carribot/grid_planner.h"
#include "workloads/carribot/grid_upscaling.h"
#include "workloads/carribot/movingai_scenario_reader.h"
#include "workloads/carribot/path_output.h"
#include "workloads/carribot/path_plot.h"
#include "workloads/rcbench/commands.h"
#include "workloads/rcbench/map_options.h"
#include "workloads/rcbench/number_checks.h"
#include "workloads/rcbench/progress_bar.h"

namespace rc {
namespace {

constexpr int kExitNoPath = ToInt(ExitCode::kNoPath);
constexpr double kOptimalTolerance = 1e-4;  // cells; the .scen files print 8 decimals

struct CarribotCli {
  std::string map_path, scen_path;
  double resolution_m = 0.0;   // 0: the map format's own (1 m per cell for MovingAI)
  MapLoadOptions map_options;  // thresholds
  int map_scale = 1;
  long scenario = -1;
  std::vector<int> start, goal;
  std::vector<int> offset;  // cells of the scaled map, added to start and goal after --map-scale
  int start_heading = kAnyHeading, goal_heading = kAnyHeading;
  double weight = 1.0;
  std::string footprint;  // "WxL" in metres
  int headings = 8;
  std::string collision_mode = "precomputed";
  std::string checker = "kernel";
  std::uint64_t max_expansions = 0;
  std::string timeline_path, path_path, plot_path;
  bool quiet = false;
  SchedulerCli scheduler;
};

using Query = CarribotQuery;

RectangleFootprint ParseFootprint(const std::string& text, const CarribotCli& cli) {
  const std::size_t x = text.find_first_of("xX");
  RectangleFootprint f;
  try {
    if (x == std::string::npos) throw std::invalid_argument("no x");
    std::size_t used_w = 0, used_l = 0;
    f.width_m = std::stod(text.substr(0, x), &used_w);
    f.length_m = std::stod(text.substr(x + 1), &used_l);
    if (used_w != x || used_l != text.size() - x - 1) throw std::invalid_argument("trailing text");
  } catch (const std::exception&) {
    throw UsageError("--footprint '" + text + "' is not WIDTHxLENGTH in metres, e.g. 0.4x0.8");
  }
  f.heading_count = cli.headings;
  if (cli.collision_mode == "precomputed")
    f.check_mode = FootprintCheckMode::kPrecomputed;
  else
    f.check_mode = FootprintCheckMode::kPerExpansion;
  return f;
}

OccupancyGrid LoadGrid(const CarribotCli& cli, OccupancyGrid* original) {
  MapLoadOptions options = cli.map_options;
  if (cli.resolution_m > 0) options.resolution_m = cli.resolution_m;
  LoadedMap loaded = LoadMap(cli.map_path, options);
  if (loaded.grid.CountCells(CellState::kFree) == 0)
    throw InputError(cli.map_path, 0, "", "the map has no free cell; there is nothing to plan on");
  PrintMapLines(std::cout, cli.map_path, loaded);
  *original = loaded.grid;
  if (cli.map_scale == 1) return std::move(loaded.grid);
  OccupancyGrid scaled = UpscaleGrid(loaded.grid, cli.map_scale);
  std::cout << "map scale " << cli.map_scale << ": " << scaled.size_x() << " x " << scaled.size_y() << " cells of "
            << scaled.resolution_m() << " m (start and goal cells multiplied by " << cli.map_scale
            << ", as RoWild's --scale-map)\n";
  return scaled;
}

std::vector<Query> MakeQueries(const CarribotCli& cli, const OccupancyGrid& original) {
  const int s = cli.map_scale;
  std::vector<Query> queries;
  if (cli.scen_path.empty()) {
    const GridPose start{cli.start[0], cli.start[1], cli.start_heading};
    const GridPose goal{cli.goal[0], cli.goal[1], cli.goal_heading};
    for (const auto& [name, p] : {std::pair{"--start", start}, std::pair{"--goal", goal}})
      if (!original.Contains(p.x, p.y))
        throw UsageError(std::string(name) + " " + std::to_string(p.x) + "," + std::to_string(p.y) +
                         " is outside the " + std::to_string(original.size_x()) + " x " +
                         std::to_string(original.size_y()) + " map");
    const int dx = cli.offset.empty() ? 0 : cli.offset[0], dy = cli.offset.empty() ? 0 : cli.offset[1];
    const GridPose scaled_start{start.x * s + dx, start.y * s + dy, start.heading};
    const GridPose scaled_goal{goal.x * s + dx, goal.y * s + dy, goal.heading};
    const long size_x = static_cast<long>(original.size_x()) * s, size_y = static_cast<long>(original.size_y()) * s;
    for (const auto& [name, p] : {std::pair{"--start", scaled_start}, std::pair{"--goal", scaled_goal}})
      if (p.x < 0 || p.y < 0 || p.x >= size_x || p.y >= size_y)
        throw UsageError(std::string(name) + " with --offset " + std::to_string(dx) + "," + std::to_string(dy) +
                         " is cell " + std::to_string(p.x) + "," + std::to_string(p.y) + ", outside the " +
                         std::to_string(size_x) + " x " + std::to_string(size_y) + " scaled map");
    queries.push_back({0, std::nullopt, scaled_start, scaled_goal, std::nullopt, "query"});
    return queries;
  }
  const MovingAiScenarioFile file = ReadMovingAiScenarios(cli.scen_path);
  CheckScenariosMatchMap(file, original);
  if (file.scenarios.empty()) throw InputError(cli.scen_path, 0, "", "the file holds no scenario");
  const std::string map_file = std::filesystem::path(cli.map_path).filename().string();
  if (file.scenarios.front().map_name != map_file)
    std::cerr << "rcbench: warning: " << cli.scen_path << " names map '" << file.scenarios.front().map_name
              << "', not '" << map_file << "' (sizes match; planning anyway)\n";
  if (cli.scenario >= static_cast<long>(file.scenarios.size()))
    throw UsageError("--scenario " + std::to_string(cli.scenario) + " is outside [0, " +
                     std::to_string(file.scenarios.size()) + ")");
  for (long i = 0; i < static_cast<long>(file.scenarios.size()); ++i) {
    if (cli.scenario >= 0 && i != cli.scenario) continue;
    const MovingAiScenario& sc = file.scenarios[i];
    queries.push_back({i,
                       sc.bucket,
                       {sc.start_x * s, sc.start_y * s, cli.start_heading},
                       {sc.goal_x * s, sc.goal_y * s, cli.goal_heading},
                       s == 1 ? std::optional<double>(sc.optimal_length) : std::nullopt,
                       "scenario " + std::to_string(i) + " (line " + std::to_string(sc.line) + ")"});
  }
  return queries;
}

void CheckUsage(const CarribotCli& cli) {
  const bool pair = !cli.start.empty() || !cli.goal.empty();
  if (cli.scen_path.empty() == !pair) throw UsageError("give either --scen FILE.scen or --start X,Y and --goal X,Y");
  if (pair && (cli.start.empty() || cli.goal.empty())) throw UsageError("--start and --goal go together");
  for (const int h : {cli.start_heading, cli.goal_heading})
    if (h != kAnyHeading && (h < 0 || h >= cli.headings))
      throw UsageError("heading index " + std::to_string(h) + " is outside [0, " + std::to_string(cli.headings) + ")");
  CheckOutputPaths({cli.timeline_path, cli.path_path, cli.plot_path});
}

std::string Describe(const PlannerOptions& o, const CarribotResult& run, FootprintCheckerKind checker) {
  std::ostringstream out;
  if (o.heuristic_weight == 1.0)
    out << "A*";
  else
    out << "weighted A* (weight " << o.heuristic_weight << ")";
  out << ", octile heuristic, ties to larger g then first pushed; robot: ";
  if (!o.footprint) return out.str() + "point (8-connected, no corner cutting)";
  const RectangleFootprint& f = *o.footprint;
  const bool kernel = checker == FootprintCheckerKind::kKernel;
  out << f.width_m << " m x " << f.length_m << " m rectangle (width x length), " << f.heading_count
      << " headings, turn cost " << run.turn_cost_cells << " cells, "
      << (f.check_mode == FootprintCheckMode::kPrecomputed
              ? (kernel ? "configuration space precomputed on the collision kernel"
                        : "configuration space precomputed from exact stencils")
              : (kernel ? "per-expansion checks on the collision kernel" : "per-expansion checks (rasterized checker)"))
      << ", set-up " << run.setup_wall_s << " s";
  return out.str();
}

// Returns the process exit code: 0, or kExitNoPath.
int Run(const CarribotCli& cli) {
  CheckUsage(cli);
  PlannerOptions options;
  options.heuristic_weight = cli.weight;
  options.max_expansions = cli.max_expansions;
  if (!cli.footprint.empty()) options.footprint = ParseFootprint(cli.footprint, cli);
  std::string error;
  if (!options.IsValid(&error)) throw UsageError(error);

  OccupancyGrid original;
  const OccupancyGrid grid = LoadGrid(cli, &original);
  const std::vector<Query> queries = MakeQueries(cli, original);
  if (queries.size() > 1 && (!cli.path_path.empty() || !cli.plot_path.empty()))
    throw UsageError("--path and --plot need a single query: add --scenario I, or use --start/--goal");

  CarribotSettings settings;
  settings.planner = options;
  settings.checker = ParseFootprintCheckerKind(cli.checker);
  settings.ledger = ToLedgerOptions(cli.scheduler);
  settings.backend_params = BackendParametersOf(cli.scheduler);
  const bool no_pricing = cli.scheduler.no_pricing;
  settings.price_backends = !no_pricing;
  if (!options.footprint && !no_pricing)
    std::cout << "note: a point robot checks grid cells directly; no collision kernel runs, nothing is priced\n";
  if (options.footprint && settings.checker == FootprintCheckerKind::kRasterized && !no_pricing)
    std::cout << "note: the rasterized checker is the CPU reference; nothing is priced\n";

  CarribotResult run;
  {
    ProgressBar bar("carribot", !cli.quiet && queries.size() > 1);
    run = RunCarribot(grid, queries, settings, false,
                      [&](std::size_t done, std::size_t total) { bar.Update(done, total); });
  }
  std::vector<PlanResult> results;
  for (const CarribotRow& row : run.rows) results.push_back(row.result);
  std::cout << "planner: " << Describe(options, run, settings.checker) << "\n";

  // Outputs only after every query ran, so a failure leaves no partial file.
  if (!cli.timeline_path.empty()) {
    WriteCarribotTimeline(cli.timeline_path, queries, run);
  }
  const PlanResult& first = results.front();
  if (queries.size() == 1 && first.found()) {
    if (!cli.path_path.empty()) {
      WritePathCsv(cli.path_path, first, grid.resolution_m(), run.heading_count);
    }
    if (!cli.plot_path.empty()) {
      WritePathPlot(cli.plot_path, grid, first, PathPlotOptions{options.footprint, 24});
    }
  }

  std::size_t found = 0, optimal_checked = 0, optimal_matched = 0;
  std::uint64_t expanded = 0;
  double wall_s = 0.0, worst_gap = 0.0;
  const bool expect_optimal = !options.footprint && options.heuristic_weight == 1.0;
  for (std::size_t i = 0; i < results.size(); ++i) {
    const PlanResult& r = results[i];
    expanded += r.expanded;
    wall_s += r.wall_s;
    if (!r.found()) continue;
    ++found;
    if (expect_optimal && queries[i].optimal_length) {
      ++optimal_checked;
      const double gap = std::abs(r.length_cells - *queries[i].optimal_length);
      worst_gap = std::max(worst_gap, gap);
      if (gap <= kOptimalTolerance) ++optimal_matched;
    }
  }
  if (queries.size() == 1 && first.found())
    std::cout << "path: " << first.length_cells << " cells = " << first.length_m << " m (" << first.path.size()
              << " states, " << first.turns << " turns)\n";
  std::cout << "found " << found << " of " << queries.size() << " paths; " << expanded << " expansions in " << wall_s
            << " s (" << (wall_s > 0 ? expanded / wall_s : 0.0) << " per s)\n";
  if (optimal_checked > 0)
    std::cout << "optimal length matched (1e-4 cells): " << optimal_matched << " of " << optimal_checked
              << " (largest difference " << worst_gap << " cells)\n";
  PrintCarribotPricing(std::cout, run, settings);
  for (const auto& [path, what] :
       {std::pair{cli.timeline_path, "timeline"}, std::pair{cli.path_path, "path"}, std::pair{cli.plot_path, "plot"}})
    if (!path.empty() && (std::string(what) == "timeline" || (queries.size() == 1 && first.found())))
      std::cout << what << ": " << path << "\n";
  if (found == queries.size()) return 0;
  int shown = 0;
  for (std::size_t i = 0; i < results.size() && shown < 5; ++i)
    if (!results[i].found()) {
      std::cout << queries[i].origin << ": " << ToString(results[i].status) << ": " << results[i].message << "\n";
      ++shown;
    }
  if (queries.size() - found > 5) std::cout << "... and " << queries.size() - found - 5 << " more without a path\n";
  return kExitNoPath;
}

}  // namespace

void AddCarribotCommand(CLI::App& app) {
  auto cli = std::make_shared<CarribotCli>();
  CLI::App* cmd =
      app.add_subcommand("carribot",
                         "Grid A* for a point robot or a rectangular footprint with headings (CarriBot), on MovingAI "
                         "scenarios or one start/goal pair");
  cmd->add_option("--map", cli->map_path, "Map file: MovingAI .map, or any format rcbench reads")->required();
  cmd->add_option("--scen", cli->scen_path, "MovingAI scenario file (.scen); plans every scenario unless --scenario");
  cmd->add_option("--scenario", cli->scenario,
                  "Plan only scenario I of --scen (index, 0-based, in file order); default: every scenario")
      ->check(CLI::NonNegativeNumber);
  auto* start = cmd->add_option("--start", cli->start, "Start cell X,Y (cells: column, row of the map)")
                    ->expected(2)
                    ->delimiter(',');
  cmd->add_option("--goal", cli->goal, "Goal cell X,Y (cells: column, row of the map)")->expected(2)->delimiter(',');
  cmd->add_option("--weight", cli->weight,
                  "Heuristic weight (unitless, >= 1; 1 = optimal A*, w > 1: cost <= w * optimal)")
      ->capture_default_str();
  auto* footprint = cmd->add_option("--footprint", cli->footprint,
                                    "Rectangular robot WIDTHxLENGTH (m, across x along the heading), e.g. 0.4x0.8; "
                                    "default: a point robot");
  cmd->add_option("--headings", cli->headings, "Heading count of a footprint robot (count: 8 or 16)")
      ->check(CLI::IsMember({8, 16}))
      ->needs(footprint)
      ->capture_default_str();
  cmd->add_option("--start-heading", cli->start_heading,
                  "Start heading (index k: angle 2*pi*k/headings from +x); "
                  "default: any collision-free heading")
      ->needs(footprint);
  cmd->add_option("--goal-heading", cli->goal_heading, "Goal heading (index k); default: any")->needs(footprint);
  cmd->add_option("--collision-mode", cli->collision_mode,
                  "precomputed (configuration space: one query per cell and heading, in launches of up to 65536, "
                  "built once and shared by every query) | per-expansion (one launch per A* expansion: its "
                  "successors' footprints)")
      ->check(CLI::IsMember({"precomputed", "per-expansion"}))
      ->needs(footprint)
      ->capture_default_str();
  cmd->add_option("--checker", cli->checker,
                  "Footprint collision checker: kernel (OBB vs the map's quadtree on the collision kernel, priced on "
                  "every backend) | rasterized (exact CPU reference, not priced)")
      ->check(CLI::IsMember({"kernel", "rasterized"}))
      ->needs(footprint)
      ->capture_default_str();
  AddSchedulerOptions(*cmd, cli->scheduler, "tree nodes per kernel query");
  cmd->add_option("--max-expansions", cli->max_expansions, "Stop a query after N expansions (count; 0 = no limit)")
      ->capture_default_str();
  cmd->add_option("--resolution,--map-resolution", cli->resolution_m,
                  "Cell size (m) for MovingAI maps (default 1) and images")
      ->check(FinitePositive());
  cmd->add_option(
         "--map-scale", cli->map_scale,
         "Split every cell into NxN cells (count N; RoWild's --scale-map); start and goal cells are multiplied by N")
      ->check(CLI::Range(1, 16))
      ->capture_default_str();
  cmd->add_option("--offset", cli->offset,
                  "Cells DX,DY of the scaled map added to --start and --goal after the --map-scale multiplication "
                  "(cells; e.g. 5,2 puts a 10x4-cell car's centre where RoWild puts its corner, at any scale)")
      ->expected(2)
      ->delimiter(',')
      ->needs(start);
  AddMapThresholdOptions(*cmd, cli->map_options);
  cmd->add_option("--timeline", cli->timeline_path, "Write one CSV row per query here");
  cmd->add_option("--path", cli->path_path, "Write the path (cells and metres, CSV) of a single query here");
  cmd->add_option("--plot", cli->plot_path, "Write a PNG of a single query's path on the map here");
  cmd->add_flag("--quiet", cli->quiet, "No progress bar");
  cmd->footer(ExitCodeFooter(
      "at least one query found no path (goal unreachable, start or goal on a blocked cell or with the footprint "
      "in collision, or --max-expansions reached); every output is still written, and the timeline's status "
      "column says why each query failed"));
  cmd->callback([cli] { ExitUnlessSuccess(Run(*cli)); });
}

}  // namespace rc
