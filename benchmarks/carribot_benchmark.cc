// CarriBot planning speed: grid A* on the MovingAI maps, and the RoWild
// CarriBot query on the Intel map at scales 1, 2 and 4.
//
//   BM_MovingAiBucket/<map>/<bucket>  every scenario of one .scen bucket per
//       iteration (point robot, A*); counters: expansions per second and
//       seconds per scenario. Buckets 0, 1/4, 1/2, 3/4 and the last of each
//       map (path lengths grow with the bucket).
//   BM_IntelRoWildQuery/<scale>/<mode>  one query, set-up included, as
//       RoWild's wall time is for a whole run. mode 0: point robot; 1: the
//       footprint with a precomputed configuration space (exact stencils);
//       2: the footprint with per-expansion checks (exact rasterized
//       checker); 3: the configuration space filled by the collision kernel
//       (KernelFootprintChecker, one OBB query per cell and heading); 4:
//       per-expansion checks on the collision kernel. Modes 3 and 4 run the
//       kernel on the host and do not price it (pricing has its own
//       benchmark); counters kernel_queries and nodes_per_query say what a
//       backend would be asked to do.
//   BM_IntelRoWildQueryDefaultPath/<scale>/<pricing>  the same query on
//       the path `rcbench carribot --footprint` takes by default
//       (RunCarribot: the configuration space filled by the collision
//       kernel, every launch priced on every backend with the CLI's default
//       ledger options; pricing 0: --no-pricing), map loading and the
//       kernel's tree included. The end-to-end comparison with RoWild's
//       process (wall time and peak memory, start-up included) is
//       scripts/carribot_vs_rowild.py; docs/carribot_performance.md has both.
//
// RoWild's query (cmu-roboarch/rowild, e2e/CarriBot/harness.cpp): Intel.map
// scaled by 1, 2 or 4 (--scale-map; each cell becomes s x s cells), start
// (227, 33, theta 0) and goal (59, 217, theta 0) multiplied by s, a 10 x 4
// cell car (length x width, not scaled), 8 headings, Euclidean heuristic,
// weight 1; its motions are turns of 45 degrees (free) and one step forward or
// back along the heading. RoWild's (x, y) is the car's corner with the body in
// [x, x + 10] x [y, y + 4] at theta 0, so our centred footprint starts and
// ends at the corner plus (5, 2) cells, heading 0. Our motion model differs
// (8 translations at any heading, turns cost the corner's arc), so expansion
// counts are not comparable one to one; the path and the map sizes are.
// RoWild's wall times on this machine: 0.59 s, 2.62 s, 12.3 s
// (../shared/REFERENCE.md section 3).
//
// Without ../shared/data the benchmarks skip with a message.
#include <chrono>
#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include <benchmark/benchmark.h>

#include "backends/scheduler/scheduler_cli.h"
#include "maps/movingai_map_loader.h"
#include "workloads/carribot/carribot_run.h"
#include "workloads/carribot/grid_planner.h"
#include "workloads/carribot/grid_upscaling.h"
#include "workloads/carribot/kernel_footprint_checker.h"
#include "workloads/carribot/movingai_scenario_reader.h"

namespace rc {
namespace {

const char* const kMovingAiMaps[] = {"den312d.map", "Boston_0_256.map", "64room_005.map", "maze512-32-9.map"};

std::string DataPath(const std::string& relative) { return std::string(RC_SHARED_DATA_DIR) + "/" + relative; }

struct LoadedScenarios {
  OccupancyGrid grid;
  std::map<int, std::vector<MovingAiScenario>> buckets;
  std::unique_ptr<GridPlanner> planner;
};

// Loaded once per map; null when the data is absent.
LoadedScenarios* Scenarios(const std::string& map_name) {
  static std::map<std::string, std::unique_ptr<LoadedScenarios>> cache;
  auto it = cache.find(map_name);
  if (it != cache.end()) return it->second.get();
  std::unique_ptr<LoadedScenarios> loaded;
  const std::string path = DataPath("movingai/" + map_name);
  if (std::filesystem::exists(path) && std::filesystem::exists(path + ".scen")) {
    loaded = std::make_unique<LoadedScenarios>();
    loaded->grid = LoadMovingAiMap(path);
    for (const MovingAiScenario& s : ReadMovingAiScenarios(path + ".scen").scenarios)
      loaded->buckets[s.bucket].push_back(s);
    loaded->planner = GridPlanner::Create(loaded->grid, PlannerOptions{});
  }
  return cache.emplace(map_name, std::move(loaded)).first->second.get();
}

void BM_MovingAiBucket(benchmark::State& state, const std::string& map_name, int bucket) {
  LoadedScenarios* data = Scenarios(map_name);
  if (data == nullptr) {
    state.SkipWithError(("shared data absent: " + DataPath("movingai/" + map_name)).c_str());
    return;
  }
  const std::vector<MovingAiScenario>& scenarios = data->buckets[bucket];
  std::uint64_t expanded = 0, planned = 0;
  for (auto _ : state) {
    for (const MovingAiScenario& s : scenarios) {
      const PlanResult r = data->planner->Plan({s.start_x, s.start_y}, {s.goal_x, s.goal_y});
      benchmark::DoNotOptimize(r.length_cells);
      expanded += r.expanded;
      ++planned;
    }
  }
  state.counters["expansions_per_s"] = benchmark::Counter(static_cast<double>(expanded), benchmark::Counter::kIsRate);
  state.counters["s_per_scenario"] =
      benchmark::Counter(static_cast<double>(planned), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["scenarios"] = static_cast<double>(scenarios.size());
}

void BM_IntelRoWildQuery(benchmark::State& state) {
  const int scale = static_cast<int>(state.range(0));
  const int mode = static_cast<int>(state.range(1));
  const std::string path = DataPath("intel/Intel.map");
  if (!std::filesystem::exists(path)) {
    state.SkipWithError(("shared data absent: " + path).c_str());
    return;
  }
  const OccupancyGrid grid = UpscaleGrid(LoadMovingAiMap(path), scale);
  PlannerOptions options;
  GridPose start{227 * scale, 33 * scale}, goal{59 * scale, 217 * scale};
  if (mode != 0) {
    const double cell = grid.resolution_m();
    options.footprint = RectangleFootprint{4 * cell, 10 * cell, 8,
                                           mode == 1 || mode == 3 ? FootprintCheckMode::kPrecomputed
                                                                  : FootprintCheckMode::kPerExpansion};
    start = {start.x + 5, start.y + 2, 0};
    goal = {goal.x + 5, goal.y + 2, 0};
  }
  const bool on_kernel = mode >= 3;
  PlanResult result;
  double setup_s = 0.0;
  std::uint64_t kernel_queries = 0, node_visits = 0;
  for (auto _ : state) {
    // The tree is built inside the loop: it is part of the kernel's set-up.
    std::unique_ptr<KernelFootprintChecker> kernel;
    const auto t0 = std::chrono::steady_clock::now();
    if (on_kernel) kernel = std::make_unique<KernelFootprintChecker>(grid);
    const double tree_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const std::unique_ptr<GridPlanner> planner = GridPlanner::Create(grid, options, kernel.get());
    result = planner->Plan(start, goal);
    setup_s = tree_s + planner->setup_wall_s();
    if (kernel) kernel_queries = kernel->kernel_queries(), node_visits = kernel->node_visits();
  }
  if (!result.found()) {
    state.SkipWithError((std::string("no path: ") + result.message).c_str());
    return;
  }
  state.counters["setup_s"] = setup_s;
  state.counters["plan_s"] = result.wall_s;
  state.counters["expanded"] = static_cast<double>(result.expanded);
  state.counters["expansions_per_s"] = result.expanded / result.wall_s;
  state.counters["collision_queries"] = static_cast<double>(result.collision_queries);
  state.counters["path_length_m"] = result.length_m;
  state.counters["cells"] = static_cast<double>(grid.cell_count());
  if (on_kernel) {
    state.counters["kernel_queries"] = static_cast<double>(kernel_queries);
    state.counters["nodes_per_query"] = kernel_queries ? static_cast<double>(node_visits) / kernel_queries : 0.0;
  }
}

BENCHMARK(BM_IntelRoWildQuery)
    ->ArgNames({"scale", "mode"})
    ->ArgsProduct({{1, 2, 4}, {0, 1, 2, 3, 4}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_IntelRoWildQueryDefaultPath(benchmark::State& state) {
  const int scale = static_cast<int>(state.range(0));
  const bool pricing = state.range(1) != 0;
  const std::string path = DataPath("intel/Intel.map");
  if (!std::filesystem::exists(path)) {
    state.SkipWithError(("shared data absent: " + path).c_str());
    return;
  }
  CarribotSettings settings;
  settings.price_backends = pricing;
  const SchedulerCli cli_defaults;
  settings.ledger = ToLedgerOptions(cli_defaults);
  settings.backend_params = BackendParametersOf(cli_defaults);
  CarribotResult run;
  for (auto _ : state) {
    const OccupancyGrid grid = UpscaleGrid(LoadMovingAiMap(path), scale);
    const double cell = grid.resolution_m();
    settings.planner.footprint = RectangleFootprint{4 * cell, 10 * cell, 8, FootprintCheckMode::kPrecomputed};
    // RoWild's corner (227, 33) -> (59, 217) times the scale, plus (5, 2)
    // cells to the car's centre (rcbench carribot --offset 5,2).
    const CarribotQuery query{0,
                              std::nullopt,
                              {227 * scale + 5, 33 * scale + 2, 0},
                              {59 * scale + 5, 217 * scale + 2, 0},
                              std::nullopt,
                              "RoWild's Intel query"};
    run = RunCarribot(grid, {query}, settings, true);
  }
  if (run.rows.empty() || !run.rows.front().result.found()) {
    state.SkipWithError("no path");
    return;
  }
  state.counters["setup_s"] = run.setup_wall_s;
  state.counters["plan_s"] = run.rows.front().result.wall_s;
  state.counters["pricing_s"] = run.pricing_wall_s;
  state.counters["kernel_queries"] = static_cast<double>(run.setup_kernel.queries);
  state.counters["nodes_per_query"] = run.setup_kernel.NodesPerQuery();
  state.counters["path_length_m"] = run.rows.front().result.length_m;
}

BENCHMARK(BM_IntelRoWildQueryDefaultPath)
    ->ArgNames({"scale", "pricing"})
    ->ArgsProduct({{1, 2, 4}, {1, 0}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Buckets exist only once the .scen files are read, so these register at
// start-up (before main parses the command line).
const bool kRegistered = [] {
  for (const char* map_name : kMovingAiMaps) {
    const LoadedScenarios* data = Scenarios(map_name);
    if (data == nullptr || data->buckets.empty()) {
      benchmark::RegisterBenchmark(("BM_MovingAiBucket/" + std::string(map_name)).c_str(), BM_MovingAiBucket,
                                   std::string(map_name), 0);
      continue;
    }
    const int last = data->buckets.rbegin()->first;
    for (const int bucket : {0, last / 4, last / 2, 3 * last / 4, last}) {
      if (data->buckets.count(bucket) == 0) continue;
      benchmark::RegisterBenchmark(
          ("BM_MovingAiBucket/" + std::string(map_name) + "/" + std::to_string(bucket)).c_str(), BM_MovingAiBucket,
          std::string(map_name), bucket)
          ->Unit(benchmark::kMillisecond)
          ->UseRealTime();
    }
  }
  return true;
}();

}  // namespace
}  // namespace rc

BENCHMARK_MAIN();
