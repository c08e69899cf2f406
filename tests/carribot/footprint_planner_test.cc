// The footprint planner: a point footprint reproduces the octile optimum;
// real footprints give paths that are collision-free at every state and
// along every motion (checked by dense sampling with the exact checker), and
// never shorter than the point robot's; per-expansion checking and the
// precomputed configuration space give identical searches.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "carribot/carribot_test_util.h"
#include "maps/movingai_map_loader.h"
#include "support/test_data.h"
#include "workloads/carribot/grid_planner.h"
#include "workloads/carribot/movingai_scenario_reader.h"
#include "workloads/carribot/rasterized_footprint_checker.h"

namespace rc {
namespace {

constexpr double kTwoPi = 6.283185307179586;

PlannerOptions FootprintOptions(double width_m, double length_m, int headings,
                                FootprintCheckMode mode = FootprintCheckMode::kPrecomputed) {
  PlannerOptions o;
  o.footprint = RectangleFootprint{width_m, length_m, headings, mode};
  return o;
}

// The motion between consecutive path states, sampled at `samples` poses
// (ends included) and each checked with the exact checker. Returns an empty
// string when every sample is free, else what collided.
std::string CheckMotionBySampling(RasterizedFootprintChecker& checker, const PathState& a, const PathState& b,
                                  const RectangleFootprint& f, int samples) {
  const int n = f.heading_count;
  const int turn = ((b.heading - a.heading) % n + n) % n;
  const bool is_turn = a.x == b.x && a.y == b.y;
  if (is_turn ? (turn != 1 && turn != n - 1)
              : (a.heading != b.heading || std::abs(a.x - b.x) > 1 || std::abs(a.y - b.y) > 1))
    return "consecutive states are not one motion apart";
  const double angle_a = kTwoPi * a.heading / n;
  const double angle_step = turn == 1 ? kTwoPi / n : -kTwoPi / n;
  for (int k = 0; k <= samples; ++k) {
    const double t = static_cast<double>(k) / samples;
    const double angle = is_turn ? angle_a + t * angle_step : angle_a;
    const FootprintPose pose{{a.x + 0.5 + t * (b.x - a.x), a.y + 0.5 + t * (b.y - a.y)},
                             {0.5 * f.length_m, 0.5 * f.width_m, {std::cos(angle), std::sin(angle)}}};
    if (checker.Collides(pose)) return "collision at t = " + std::to_string(t);
  }
  return "";
}

void ExpectValidFootprintPath(const OccupancyGrid& grid, const PlanResult& r, const RectangleFootprint& f,
                              double point_optimum) {
  RasterizedFootprintChecker checker(grid);
  ASSERT_FALSE(r.path.empty());
  for (std::size_t i = 0; i + 1 < r.path.size(); ++i) {
    const std::string problem = CheckMotionBySampling(checker, r.path[i], r.path[i + 1], f, 64);
    ASSERT_TRUE(problem.empty()) << "motion " << i << " (" << r.path[i].x << ", " << r.path[i].y << ", "
                                 << r.path[i].heading << ") -> (" << r.path[i + 1].x << ", " << r.path[i + 1].y << ", "
                                 << r.path[i + 1].heading << "): " << problem;
  }
  EXPECT_GE(r.translation_cells, point_optimum - 1e-6);  // .scen lengths carry 8 decimals
  EXPECT_GE(r.length_cells, r.translation_cells);
}

TEST(FootprintPlanner, PointFootprintHasOctileOptimalLengthsOnDen312d) {
  RC_REQUIRE_SHARED_DATA("movingai/den312d.map");
  const std::string map = test::SharedDataPath("movingai/den312d.map");
  const OccupancyGrid grid = LoadMovingAiMap(map);
  const MovingAiScenarioFile file = ReadMovingAiScenarios(map + ".scen");
  for (const int headings : {8, 16}) {
    const auto planner = GridPlanner::Create(grid, FootprintOptions(0.0, 0.0, headings));
    EXPECT_EQ(planner->turn_cost_cells(), 0.0);
    for (const MovingAiScenario& s : file.scenarios) {
      const PlanResult r = planner->Plan({s.start_x, s.start_y}, {s.goal_x, s.goal_y});
      ASSERT_TRUE(r.found()) << "line " << s.line;
      ASSERT_NEAR(r.length_cells, s.optimal_length, 1e-4) << "line " << s.line << ", " << headings << " headings";
    }
  }
}

TEST(FootprintPlanner, PointFootprintMatchesPointRobotOnRandomMaps) {
  for (unsigned seed = 1; seed <= 6; ++seed) {
    const OccupancyGrid grid = test::RandomGrid(30, 25, 0.05 * seed, seed);
    const auto point = GridPlanner::Create(grid, PlannerOptions{});
    const auto footprint = GridPlanner::Create(grid, FootprintOptions(0.0, 0.0, 8));
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> x(0, 29), y(0, 24);
    for (int q = 0; q < 30; ++q) {
      const GridPose a{x(rng), y(rng)}, b{x(rng), y(rng)};
      const PlanResult p = point->Plan(a, b), f = footprint->Plan(a, b);
      ASSERT_EQ(p.status, f.status);
      if (p.found()) {
        EXPECT_NEAR(p.length_cells, f.length_cells, 1e-9);
      }
    }
  }
}

struct FootprintCase {
  double width_cells, length_cells;
  int headings;
};

void ExpectValidPathsOnScenarios(const std::string& map_name, const FootprintCase& c, std::size_t stride) {
  const std::string map = test::SharedDataPath("movingai/" + map_name);
  const OccupancyGrid grid = LoadMovingAiMap(map);
  const MovingAiScenarioFile file = ReadMovingAiScenarios(map + ".scen");
  const PlannerOptions options = FootprintOptions(c.width_cells, c.length_cells, c.headings);
  const auto planner = GridPlanner::Create(grid, options);
  std::size_t found = 0, tried = 0;
  for (std::size_t i = 0; i < file.scenarios.size(); i += stride, ++tried) {
    const MovingAiScenario& s = file.scenarios[i];
    const PlanResult r = planner->Plan({s.start_x, s.start_y}, {s.goal_x, s.goal_y});
    if (!r.found()) continue;
    ++found;
    ExpectValidFootprintPath(grid, r, *options.footprint, s.optimal_length);
    if (::testing::Test::HasFatalFailure()) return;
  }
  EXPECT_GT(found, tried / 4) << "too few footprint paths to test anything";
}

TEST(FootprintPlanner, PathsAreCollisionFreeAndNoShorterOnDen312d) {
  RC_REQUIRE_SHARED_DATA("movingai/den312d.map");
  for (const FootprintCase& c : {FootprintCase{0.6, 1.8, 8}, FootprintCase{1.0, 1.0, 16}, FootprintCase{1.5, 2.2, 16}})
    ExpectValidPathsOnScenarios("den312d.map", c, 3);
}

TEST(FootprintPlanner, PathsAreCollisionFreeAndNoShorterOnBoston) {
  RC_REQUIRE_SHARED_DATA("movingai/Boston_0_256.map");
  ExpectValidPathsOnScenarios("Boston_0_256.map", {2.0, 4.0, 8}, 25);
}

TEST(FootprintPlanner, PathsAreCollisionFreeOnRandomMaps) {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const OccupancyGrid grid = test::RandomGrid(40, 30, 0.04 * seed, 100 + seed);
    const PlannerOptions options = FootprintOptions(0.7, 2.1, seed % 2 == 0 ? 8 : 16);
    const auto planner = GridPlanner::Create(grid, options);
    const auto point = GridPlanner::Create(grid, PlannerOptions{});
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> x(0, 39), y(0, 29);
    for (int q = 0; q < 25; ++q) {
      const GridPose a{x(rng), y(rng)}, b{x(rng), y(rng)};
      const PlanResult r = planner->Plan(a, b);
      if (!r.found()) continue;
      const PlanResult p = point->Plan(a, b);
      ASSERT_TRUE(p.found()) << "a footprint path exists where no point path does";
      ExpectValidFootprintPath(grid, r, *options.footprint, p.length_cells);
      if (HasFatalFailure()) return;
    }
  }
}

TEST(FootprintPlanner, PerExpansionCheckingMatchesPrecomputed) {
  const OccupancyGrid grid = test::RandomGrid(35, 28, 0.15, 21);
  for (const int headings : {8, 16}) {
    const auto pre = GridPlanner::Create(grid, FootprintOptions(0.8, 1.9, headings, FootprintCheckMode::kPrecomputed));
    RasterizedFootprintChecker checker(grid);
    const auto per =
        GridPlanner::Create(grid, FootprintOptions(0.8, 1.9, headings, FootprintCheckMode::kPerExpansion), &checker);
    std::mt19937 rng(headings);
    std::uniform_int_distribution<int> x(0, 34), y(0, 27);
    std::uint64_t queries = 0;
    for (int q = 0; q < 30; ++q) {
      const GridPose a{x(rng), y(rng)}, b{x(rng), y(rng)};
      const PlanResult r1 = pre->Plan(a, b), r2 = per->Plan(a, b);
      ASSERT_EQ(r1.status, r2.status);
      EXPECT_EQ(r1.expanded, r2.expanded);
      EXPECT_EQ(r1.collision_queries, r2.collision_queries);
      EXPECT_EQ(r1.length_cells, r2.length_cells);
      ASSERT_EQ(r1.path.size(), r2.path.size());
      for (std::size_t i = 0; i < r1.path.size(); ++i) EXPECT_EQ(r1.path[i].heading, r2.path[i].heading);
      queries += r2.collision_queries;
    }
    EXPECT_GE(checker.poses_checked(), queries);  // every motion check went through the checker
  }
}

TEST(FootprintPlanner, WeightedSearchStaysWithinItsBound) {
  RC_REQUIRE_SHARED_DATA("movingai/Boston_0_256.map");
  const std::string map = test::SharedDataPath("movingai/Boston_0_256.map");
  const OccupancyGrid grid = LoadMovingAiMap(map);
  const MovingAiScenarioFile file = ReadMovingAiScenarios(map + ".scen");
  for (const double w : {1.5, 3.0}) {
    PlannerOptions o;
    o.heuristic_weight = w;
    const auto planner = GridPlanner::Create(grid, o);
    std::uint64_t weighted = 0, optimal = 0;
    const auto astar = GridPlanner::Create(grid, PlannerOptions{});
    for (std::size_t i = 0; i < file.scenarios.size(); i += 5) {
      const MovingAiScenario& s = file.scenarios[i];
      const PlanResult r = planner->Plan({s.start_x, s.start_y}, {s.goal_x, s.goal_y});
      ASSERT_TRUE(r.found());
      EXPECT_GE(r.length_cells, s.optimal_length - 1e-4);
      EXPECT_LE(r.length_cells, w * s.optimal_length + 1e-4);
      weighted += r.expanded;
      optimal += astar->Plan({s.start_x, s.start_y}, {s.goal_x, s.goal_y}).expanded;
    }
    EXPECT_LT(weighted, optimal);  // the point of weighting
  }
}

}  // namespace
}  // namespace rc
