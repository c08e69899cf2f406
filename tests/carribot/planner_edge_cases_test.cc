// Hard cases of the planner: degenerate maps and queries give clear statuses,
// never exceptions or crashes; misuse gives exceptions.
#include "workloads/carribot/grid_planner.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "carribot/carribot_test_util.h"
#include "common/input_error.h"

namespace rc {
namespace {

using test::GridFromRows;

PlannerOptions FootprintOptions(double width_m, double length_m, int headings = 8) {
  PlannerOptions o;
  RectangleFootprint f;
  f.width_m = width_m;
  f.length_m = length_m;
  f.heading_count = headings;
  o.footprint = f;
  return o;
}

const std::vector<std::string> kTwoRooms = {
    "....@....",
    "....@....",
    "....@....",
};

TEST(PlannerEdgeCases, StartEqualsGoal) {
  for (const PlannerOptions& o : {PlannerOptions{}, FootprintOptions(0.5, 0.5)}) {
    const auto planner = GridPlanner::Create(GridFromRows(kTwoRooms), o);
    const PlanResult r = planner->Plan({1, 1}, {1, 1});
    ASSERT_EQ(r.status, PlanStatus::kFound);
    EXPECT_EQ(r.path.size(), 1u);
    EXPECT_EQ(r.length_cells, 0.0);
    EXPECT_EQ(r.expanded, 0u);
  }
}

TEST(PlannerEdgeCases, UnreachableGoalIsAResult) {
  for (const PlannerOptions& o : {PlannerOptions{}, FootprintOptions(0.2, 0.2)}) {
    const auto planner = GridPlanner::Create(GridFromRows(kTwoRooms), o);
    const PlanResult r = planner->Plan({0, 0}, {8, 2});
    EXPECT_EQ(r.status, PlanStatus::kNoPath);
    EXPECT_STREQ(ToString(r.status), "no_path");
    EXPECT_NE(r.message.find("unreachable"), std::string::npos);
    EXPECT_TRUE(r.path.empty());
    EXPECT_GT(r.expanded, 10u);  // it searched the whole left room
  }
}

TEST(PlannerEdgeCases, NoCornerCutting) {
  // The only way from (0,0) to (1,1) is the diagonal between two blocked cells.
  const auto planner = GridPlanner::Create(GridFromRows({".@", "@."}), PlannerOptions{});
  EXPECT_EQ(planner->Plan({0, 0}, {1, 1}).status, PlanStatus::kNoPath);
  const auto open = GridPlanner::Create(GridFromRows({"..", ".."}), PlannerOptions{});
  EXPECT_DOUBLE_EQ(open->Plan({0, 0}, {1, 1}).length_cells, std::sqrt(2.0));
}

TEST(PlannerEdgeCases, BlockedOrOutsideStartAndGoal) {
  const auto planner = GridPlanner::Create(GridFromRows(kTwoRooms), PlannerOptions{});
  EXPECT_EQ(planner->Plan({4, 0}, {0, 0}).status, PlanStatus::kStartInCollision);
  EXPECT_EQ(planner->Plan({0, 0}, {4, 1}).status, PlanStatus::kGoalInCollision);
  EXPECT_EQ(planner->Plan({-1, 0}, {0, 0}).status, PlanStatus::kStartOutOfMap);
  EXPECT_EQ(planner->Plan({0, 0}, {9, 0}).status, PlanStatus::kGoalOutOfMap);
  EXPECT_EQ(planner->Plan({0, 0}, {0, 3}).status, PlanStatus::kGoalOutOfMap);
  const PlanResult r = planner->Plan({4, 2}, {0, 0});
  EXPECT_NE(r.message.find("(4, 2)"), std::string::npos) << r.message;
}

TEST(PlannerEdgeCases, UnknownCellsAreBlocked) {
  const auto planner = GridPlanner::Create(GridFromRows({".?."}), PlannerOptions{});
  EXPECT_EQ(planner->Plan({0, 0}, {2, 0}).status, PlanStatus::kNoPath);
  EXPECT_EQ(planner->Plan({1, 0}, {2, 0}).status, PlanStatus::kStartInCollision);
}

TEST(PlannerEdgeCases, OneCellMaps) {
  const auto free_cell = GridPlanner::Create(GridFromRows({"."}), PlannerOptions{});
  EXPECT_EQ(free_cell->Plan({0, 0}, {0, 0}).status, PlanStatus::kFound);
  EXPECT_EQ(free_cell->Plan({0, 0}, {1, 0}).status, PlanStatus::kGoalOutOfMap);
  const auto blocked_cell = GridPlanner::Create(GridFromRows({"@"}), PlannerOptions{});
  EXPECT_EQ(blocked_cell->Plan({0, 0}, {0, 0}).status, PlanStatus::kStartInCollision);
  // A footprint larger than the only cell collides with the outside of the map.
  const auto footprint = GridPlanner::Create(GridFromRows({"."}), FootprintOptions(1.0, 1.0));
  EXPECT_EQ(footprint->Plan({0, 0}, {0, 0}).status, PlanStatus::kStartInCollision);
  const auto small = GridPlanner::Create(GridFromRows({"."}), FootprintOptions(0.9, 0.9));
  EXPECT_EQ(small->Plan({0, 0}, {0, 0}).status, PlanStatus::kFound);
}

TEST(PlannerEdgeCases, MapWithNoFreeCell) {
  for (const PlannerOptions& o : {PlannerOptions{}, FootprintOptions(0.3, 0.6)}) {
    const auto planner = GridPlanner::Create(GridFromRows({"@@@", "@@@"}), o);
    EXPECT_EQ(planner->Plan({1, 1}, {0, 0}).status, PlanStatus::kStartInCollision);
  }
}

TEST(PlannerEdgeCases, FootprintThatFitsNowhere) {
  const auto planner = GridPlanner::Create(GridFromRows(kTwoRooms), FootprintOptions(3.5, 3.5));
  const PlanResult r = planner->Plan({1, 1}, {2, 1});
  EXPECT_EQ(r.status, PlanStatus::kStartInCollision);
  EXPECT_NE(r.message.find("every heading"), std::string::npos);
}

TEST(PlannerEdgeCases, GoalHeadingIsHonoured) {
  // A 0.5 x 2.5 bar fits the one-cell corridor only lying along it; to face
  // the other way it must drive into the room, turn there and come back.
  const std::vector<std::string> map = {
      "@@@@@@@@@@@@",  // y = 0
      "............",  // the corridor, y = 1
      "@@@@@@@.....", "@@@@@@@.....", "@@@@@@@.....", "@@@@@@@.....", "@@@@@@@@@@@@",
  };
  const auto planner = GridPlanner::Create(GridFromRows(map), FootprintOptions(0.5, 2.5));
  const PlanResult reversed = planner->Plan({2, 1, 0}, {2, 1, 4});
  ASSERT_EQ(reversed.status, PlanStatus::kFound);
  EXPECT_EQ(reversed.path.back().heading, 4);
  EXPECT_EQ(reversed.turns, 4);  // a half turn, one heading step at a time
  EXPECT_GT(reversed.translation_cells, 2 * 5.0);
  EXPECT_NEAR(reversed.length_cells, reversed.translation_cells + 4 * planner->turn_cost_cells(), 1e-9);
  EXPECT_EQ(planner->Plan({2, 1, 0}, {3, 1, 2}).status, PlanStatus::kGoalInCollision);
  EXPECT_EQ(planner->Plan({2, 1, 2}, {3, 1}).status, PlanStatus::kStartInCollision);
}

TEST(PlannerEdgeCases, ExpansionLimit) {
  PlannerOptions o;
  o.max_expansions = 3;
  const auto planner = GridPlanner::Create(OccupancyGrid(10, 10, 1.0), o);
  const PlanResult r = planner->Plan({0, 0}, {9, 9});  // 9 expansions needed
  EXPECT_EQ(r.status, PlanStatus::kExpansionLimit);
  EXPECT_EQ(r.expanded, 3u);
}

TEST(PlannerEdgeCases, MisuseThrows) {
  const OccupancyGrid grid = GridFromRows(kTwoRooms);
  PlannerOptions low_weight;
  low_weight.heuristic_weight = 0.5;
  EXPECT_THROW(GridPlanner::Create(grid, low_weight), UsageError);
  PlannerOptions nan_weight;
  nan_weight.heuristic_weight = std::nan("");
  EXPECT_THROW(GridPlanner::Create(grid, nan_weight), UsageError);
  EXPECT_THROW(GridPlanner::Create(grid, FootprintOptions(-1.0, 1.0)), UsageError);
  EXPECT_THROW(GridPlanner::Create(grid, FootprintOptions(1.0, 1.0, 3)), UsageError);
  const auto point = GridPlanner::Create(grid, PlannerOptions{});
  EXPECT_THROW(point->Plan({0, 0, 1}, {1, 1}), std::invalid_argument);
  const auto footprint = GridPlanner::Create(grid, FootprintOptions(0.5, 0.5));
  EXPECT_THROW(footprint->Plan({0, 0, 8}, {1, 1}), std::invalid_argument);
}

// A planner resets only what a query touched: reusing it gives the answers of
// a fresh planner, in any order of queries.
TEST(PlannerEdgeCases, ReuseMatchesFreshPlanners) {
  const OccupancyGrid grid = test::RandomGrid(40, 30, 0.3, 9);
  for (const PlannerOptions& o : {PlannerOptions{}, FootprintOptions(0.6, 1.4)}) {
    const auto reused = GridPlanner::Create(grid, o);
    std::mt19937 rng(4);
    std::uniform_int_distribution<int> x(0, 39), y(0, 29);
    for (int q = 0; q < 40; ++q) {
      const GridPose a{x(rng), y(rng)}, b{x(rng), y(rng)};
      const PlanResult again = reused->Plan(a, b);
      const PlanResult fresh = GridPlanner::Create(grid, o)->Plan(a, b);
      ASSERT_EQ(again.status, fresh.status);
      EXPECT_EQ(again.length_cells, fresh.length_cells);
      EXPECT_EQ(again.expanded, fresh.expanded);
      EXPECT_EQ(again.collision_queries, fresh.collision_queries);
      ASSERT_EQ(again.path.size(), fresh.path.size());
      for (std::size_t i = 0; i < again.path.size(); ++i) {
        EXPECT_EQ(again.path[i].x, fresh.path[i].x);
        EXPECT_EQ(again.path[i].y, fresh.path[i].y);
        EXPECT_EQ(again.path[i].heading, fresh.path[i].heading);
      }
    }
  }
}

}  // namespace
}  // namespace rc
