// A CarriBot run on the collision kernel: every launch priced on every
// backend, identical functional results for every backend policy, launch
// costs summed per iteration, and the hard cases through the kernel.
#include "workloads/carribot/carribot_run.h"

#include <gtest/gtest.h>

#include <random>

#include <omp.h>

#include "backends/calibration/sact_kernel_record.h"
#include "carribot/carribot_test_util.h"
#include "workloads/carribot/kernel_footprint_checker.h"

namespace rc {
namespace {

CarribotSettings KernelSettings(double width_cells, double length_cells, FootprintCheckMode mode,
                                const std::string& policy = "adaptive") {
  CarribotSettings s;
  s.planner.footprint = RectangleFootprint{width_cells, length_cells, 8, mode};
  const SchedulerOptions parsed = ParseSchedulerPolicy(policy, Backend::ModelledNames());
  s.ledger.policy.kind = parsed.kind;
  s.ledger.policy.static_backend = parsed.static_backend;
  return s;
}

std::vector<CarribotQuery> RandomQueries(const OccupancyGrid& grid, int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> x(0, grid.size_x() - 1), y(0, grid.size_y() - 1);
  std::vector<CarribotQuery> queries;
  for (int i = 0; i < count; ++i) {
    CarribotQuery q;
    q.index = i;
    q.start = {x(rng), y(rng)};
    q.goal = {x(rng), y(rng)};
    queries.push_back(q);
  }
  return queries;
}

const char* const kPolicies[] = {
    "static:simt", "static:ttaplus", "static:ttaplus-p", "static:ttaplus-cr", "static:robocore", "adaptive", "oracle"};

// Every --backend value: the same paths and counters, the same per-backend
// prices (shadow costing), and the chosen backend's cycles in the row.
TEST(CarribotRun, EveryBackendPolicyGivesIdenticalPathsAndPrices) {
  const OccupancyGrid grid = test::RandomGrid(20, 15, 0.05, 8);
  const std::vector<CarribotQuery> queries = RandomQueries(grid, 5, 2);
  for (const FootprintCheckMode mode : {FootprintCheckMode::kPrecomputed, FootprintCheckMode::kPerExpansion}) {
    std::vector<CarribotResult> runs;
    for (const char* policy : kPolicies)
      runs.push_back(RunCarribot(grid, queries, KernelSettings(0.6, 1.4, mode, policy), /*keep_paths=*/true));
    const CarribotResult& first = runs.front();
    ASSERT_TRUE(first.priced);
    EXPECT_EQ(first.has_setup, mode == FootprintCheckMode::kPrecomputed);
    int found = 0;
    for (const CarribotRow& row : first.rows) found += row.result.found();
    EXPECT_GE(found, 2);
    for (std::size_t p = 0; p < runs.size(); ++p) {
      const CarribotResult& run = runs[p];
      SCOPED_TRACE(kPolicies[p]);
      ASSERT_EQ(run.rows.size(), queries.size());
      for (std::size_t i = 0; i < queries.size(); ++i) {
        const CarribotRow &a = first.rows[i], &b = run.rows[i];
        EXPECT_EQ(a.result.status, b.result.status);
        EXPECT_EQ(a.result.length_cells, b.result.length_cells);
        EXPECT_EQ(a.result.expanded, b.result.expanded);
        EXPECT_EQ(a.result.collision_queries, b.result.collision_queries);
        EXPECT_EQ(a.kernel.queries, b.kernel.queries);
        EXPECT_EQ(a.kernel.node_visits, b.kernel.node_visits);
        ASSERT_EQ(a.result.path.size(), b.result.path.size());
        for (std::size_t k = 0; k < a.result.path.size(); ++k) {
          EXPECT_EQ(a.result.path[k].x, b.result.path[k].x);
          EXPECT_EQ(a.result.path[k].y, b.result.path[k].y);
          EXPECT_EQ(a.result.path[k].heading, b.result.path[k].heading);
        }
        ASSERT_EQ(a.pricing.priced, b.pricing.priced);
        for (std::size_t k = 0; k < b.pricing.costs.size(); ++k)
          EXPECT_EQ(a.pricing.costs[k].cycles, b.pricing.costs[k].cycles);
        if (b.pricing.priced) {
          const BatchCost& chosen =
              b.pricing.costs[std::find(run.pricing.backends.begin(), run.pricing.backends.end(), b.pricing.backend) -
                              run.pricing.backends.begin()];
          EXPECT_GT(chosen.cycles, 0u);
          EXPECT_EQ(b.pricing.chosen_cycles,
                    static_cast<double>(chosen.cycles) + (b.pricing.switched ? run.pricing.switch_cost_cycles : 0.0));
        }
      }
      EXPECT_EQ(run.pricing.static_total_cycles, first.pricing.static_total_cycles);
      if (std::string(kPolicies[p]).rfind("static:", 0) == 0) {
        for (const CarribotRow& row : run.rows) EXPECT_EQ("static:" + row.pricing.backend, kPolicies[p]);
      }
    }
    // Per expansion, every query that expanded a state launched the kernel.
    if (mode == FootprintCheckMode::kPerExpansion) {
      for (const CarribotRow& row : first.rows) {
        EXPECT_EQ(row.pricing.priced, row.kernel.queries > 0);
        EXPECT_LE(row.kernel.launches, row.result.expanded + 2 * 8);  // + the start and goal heading checks
      }
    } else {
      EXPECT_EQ(first.setup_kernel.queries, grid.cell_count() * 8);
      for (const CarribotRow& row : first.rows) EXPECT_EQ(row.kernel.queries, 0u);
    }
  }
}

// The adaptive policy starts the configuration space's fill on the backend
// cheapest on the fill's first launch (its start probe): with one launch,
// the set-up iteration runs its cheapest backend.
TEST(CarribotRun, TheFillStartsOnTheBackendCheapestOnItsFirstLaunch) {
  const OccupancyGrid grid = test::RandomGrid(40, 30, 0.1, 5);
  const CarribotResult run = RunCarribot(grid, RandomQueries(grid, 1, 3),
                                         KernelSettings(0.6, 1.4, FootprintCheckMode::kPrecomputed), false);
  ASSERT_TRUE(run.has_setup);
  ASSERT_EQ(run.setup_kernel.launches, 1u);
  ASSERT_TRUE(run.setup_pricing.priced);
  std::uint64_t cheapest = run.setup_pricing.costs.front().cycles;
  for (const BatchCost& c : run.setup_pricing.costs) cheapest = std::min(cheapest, c.cycles);
  EXPECT_EQ(run.setup_pricing.chosen_cycles, static_cast<double>(cheapest)) << run.setup_pricing.backend;
  EXPECT_FALSE(run.setup_pricing.switched);
  EXPECT_GT(run.pricing_wall_s, 0.0);
}

// An iteration of many launches costs the sum of its launches priced alone.
TEST(CarribotRun, AnIterationCostsTheSumOfItsLaunches) {
  // One thread: these launches are a warp each, and prices do not depend
  // on the thread count (OpenMP fork/join would dominate the test's time).
  omp_set_num_threads(1);
  const OccupancyGrid grid = test::RandomGrid(16, 12, 0.15, 4);
  KernelFootprintChecker checker(grid);
  BackendLedger ledger(BackendParameters{}, LedgerOptions{});
  std::vector<KernelRecord> launches;
  checker.set_batch_observer([&](const CollisionBatch& batch) {
    launches.push_back(SactKernelRecord(batch));
    ledger.AddLaunch(launches.back());
  });
  PlannerOptions options;
  options.footprint = RectangleFootprint{1.0, 1.5, 8, FootprintCheckMode::kPerExpansion};
  const auto planner = GridPlanner::Create(grid, options, &checker);
  ledger.BeginIteration();
  planner->Plan({1, 1}, {14, 10});
  const LedgerIteration it = ledger.EndIteration(nullptr);
  ASSERT_GT(launches.size(), 3u);
  ASSERT_TRUE(it.priced);
  std::uint64_t queries = 0, nodes = 0;
  for (std::size_t b = 0; b < ledger.backend_names().size(); ++b) {
    const auto backend = Backend::Create(ledger.backend_names()[b], BackendParameters{});
    std::uint64_t cycles = 0;
    double energy = 0;
    for (const KernelRecord& r : launches) {
      const BatchCost c = backend->Price(r);
      cycles += c.cycles;
      energy += c.energy_joules;
    }
    EXPECT_EQ(it.costs[b].cycles, cycles) << ledger.backend_names()[b];
    EXPECT_NEAR(it.costs[b].energy_joules, energy, 1e-12 * energy);
    // Each launch pays the kernel launch.
    EXPECT_GE(it.costs[b].launch_cycles,
              launches.size() * static_cast<std::uint64_t>(BackendParameters{}.gpu.kernel_launch_cycles));
  }
  for (const KernelRecord& r : launches) queries += r.query_count(), nodes += r.total_nodes();
  EXPECT_DOUBLE_EQ(it.nodes_per_query, static_cast<double>(nodes) / queries);
  // The next iteration starts empty.
  ledger.BeginIteration();
  EXPECT_FALSE(ledger.EndIteration(nullptr).priced);
}

// The issue's hard cases, through the kernel checker in both modes.
TEST(CarribotRun, HardCasesThroughTheKernel) {
  struct Case {
    const char* name;
    std::vector<std::string> rows;
    double width_cells, length_cells;
    GridPose start, goal;
    PlanStatus expected;
  };
  const std::vector<std::string> two_rooms = {"....@....", "....@....", "....@...."};
  const Case cases[] = {
      {"start equals goal", two_rooms, 0.5, 0.5, {1, 1}, {1, 1}, PlanStatus::kFound},
      {"unreachable goal", two_rooms, 0.2, 0.2, {0, 0}, {8, 2}, PlanStatus::kNoPath},
      {"start blocked", two_rooms, 0.2, 0.2, {4, 0}, {0, 0}, PlanStatus::kStartInCollision},
      {"goal blocked", two_rooms, 0.2, 0.2, {0, 0}, {4, 1}, PlanStatus::kGoalInCollision},
      {"start outside", two_rooms, 0.2, 0.2, {-1, 0}, {0, 0}, PlanStatus::kStartOutOfMap},
      {"goal outside", two_rooms, 0.2, 0.2, {0, 0}, {0, 3}, PlanStatus::kGoalOutOfMap},
      {"1x1 map, footprint fits", {"."}, 0.9, 0.9, {0, 0}, {0, 0}, PlanStatus::kFound},
      {"1x1 map, footprint touches the outside", {"."}, 1.0, 1.0, {0, 0}, {0, 0}, PlanStatus::kStartInCollision},
      {"1x1 blocked map", {"@"}, 0.0, 0.0, {0, 0}, {0, 0}, PlanStatus::kStartInCollision},
      {"no free cell", {"@@@", "@@@"}, 0.3, 0.6, {1, 1}, {0, 0}, PlanStatus::kStartInCollision},
      {"fits nowhere", two_rooms, 3.5, 3.5, {1, 1}, {2, 1}, PlanStatus::kStartInCollision},
  };
  for (const Case& c : cases) {
    for (const FootprintCheckMode mode : {FootprintCheckMode::kPrecomputed, FootprintCheckMode::kPerExpansion}) {
      SCOPED_TRACE(std::string(c.name) +
                   (mode == FootprintCheckMode::kPrecomputed ? ", precomputed" : ", per expansion"));
      CarribotQuery q;
      q.start = c.start;
      q.goal = c.goal;
      // A static policy: no threshold to derive, so the case stays fast.
      const CarribotResult r = RunCarribot(test::GridFromRows(c.rows), {q},
                                           KernelSettings(c.width_cells, c.length_cells, mode, "static:simt"));
      ASSERT_EQ(r.rows.size(), 1u);
      EXPECT_EQ(r.rows[0].result.status, c.expected);
      if (c.expected != PlanStatus::kFound) {
        EXPECT_FALSE(r.rows[0].result.message.empty());
      } else {
        EXPECT_EQ(r.rows[0].result.length_cells, 0.0);
      }
      EXPECT_TRUE(r.priced);
    }
  }
}

}  // namespace
}  // namespace rc
