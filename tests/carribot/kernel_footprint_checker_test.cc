// The collision-kernel FootprintChecker: the exact answer on every cell and
// heading (conformance), off-lattice poses and the outside of the map, and
// planners that use it, in both collision modes, give the paths of the
// exact stencils.
#include "workloads/carribot/kernel_footprint_checker.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "carribot/carribot_test_util.h"
#include "carribot/footprint_checker_conformance.h"
#include "maps/movingai_map_loader.h"
#include "support/test_data.h"
#include "workloads/carribot/grid_planner.h"
#include "workloads/carribot/rasterized_footprint_checker.h"

namespace rc {
namespace {

struct Shape {
  double length_cells, width_cells;
};
// As configuration_space_test.cc: integer and half-integer sizes put edges
// exactly on cell boundaries at quarter turns, where touching must be exact.
const Shape kShapes[] = {{0, 0}, {1, 1}, {3, 1}, {2.4, 0.9}, {5, 2}, {10, 4}, {1.7, 3.3}};

TEST(KernelFootprintChecker, MatchesTheExactConfigurationSpaceOnRandomMaps) {
  for (unsigned seed = 1; seed <= 4; ++seed) {
    const OccupancyGrid grid = test::RandomGrid(23, 17, 0.08 * seed, seed);
    KernelFootprintChecker checker(grid);
    for (const Shape& shape : kShapes) {
      for (const int n : {8, 16}) {
        const FootprintStencils stencils(shape.length_cells, shape.width_cells, n);
        EXPECT_TRUE(test::CheckerMatchesExactConfigurationSpace(checker, grid, stencils))
            << "seed " << seed << ", " << shape.length_cells << " x " << shape.width_cells << ", " << n;
      }
    }
    EXPECT_EQ(checker.kernel_queries(), checker.poses_checked());  // lattice centres are inside the map
    EXPECT_GT(checker.node_visits(), checker.kernel_queries());
  }
}

TEST(KernelFootprintChecker, MatchesTheExactConfigurationSpaceOnDen312d) {
  RC_REQUIRE_SHARED_DATA("movingai/den312d.map");
  const OccupancyGrid grid = LoadMovingAiMap(test::SharedDataPath("movingai/den312d.map"));
  KernelFootprintChecker checker(grid);
  for (const Shape& shape : {Shape{3, 1}, Shape{2.4, 0.9}, Shape{6, 3}}) {
    const FootprintStencils stencils(shape.length_cells, shape.width_cells, 16);
    EXPECT_TRUE(test::CheckerMatchesExactConfigurationSpace(checker, grid, stencils))
        << shape.length_cells << " x " << shape.width_cells;
  }
}

// Unknown cells are obstacles, as for the reference.
TEST(KernelFootprintChecker, UnknownCellsAreBlocked) {
  const OccupancyGrid grid = test::GridFromRows({".....", "..?..", "....."});
  KernelFootprintChecker checker(grid);
  EXPECT_TRUE(test::CheckerMatchesExactConfigurationSpace(checker, grid, FootprintStencils(1, 1, 8)));
  const FootprintStencils point(0, 0, 8);
  std::uint8_t collides = 0;
  const FootprintPose on_unknown = point.PoseAt(2, 1, 0);
  checker.CheckPoses(&on_unknown, 1, &collides);
  EXPECT_EQ(collides, 1);
}

// Off-lattice poses, partly or wholly outside the map: the reference's answer.
TEST(KernelFootprintChecker, AgreesWithTheReferenceOnRandomPoses) {
  const OccupancyGrid grid = test::RandomGrid(12, 9, 0.1, 5);
  KernelFootprintChecker kernel(grid);
  RasterizedFootprintChecker reference(grid);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> x(-1.0, 13.0), y(-1.0, 10.0), angle(0, 6.283185307179586), extent(0, 1.5);
  std::vector<FootprintPose> poses;
  for (int trial = 0; trial < 4000; ++trial) {
    const double a = angle(rng);
    poses.push_back({{x(rng), y(rng)}, {extent(rng), extent(rng), {std::cos(a), std::sin(a)}}});
  }
  std::vector<std::uint8_t> expected(poses.size()), got(poses.size());
  reference.CheckPoses(poses.data(), poses.size(), expected.data());
  kernel.CheckPoses(poses.data(), poses.size(), got.data());
  int collisions = 0;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    EXPECT_EQ(got[i], expected[i]) << "pose " << i << " at (" << poses[i].center.x << ", " << poses[i].center.y << ")";
    collisions += expected[i];
  }
  EXPECT_GT(collisions, 400);
  EXPECT_LT(collisions, 3800);
  EXPECT_EQ(kernel.batches(), 1u);                   // one call, one launch
  EXPECT_LT(kernel.kernel_queries(), poses.size());  // centres outside the map never reach the kernel
}

// The outside of the map counts as blocked, exactly at the boundary.
TEST(KernelFootprintChecker, TheOutsideOfTheMapIsBlocked) {
  const OccupancyGrid open(6, 4, 1.0);
  KernelFootprintChecker checker(open);
  const auto collides = [&](double cx, double cy, double half_length, double half_width) {
    const FootprintPose pose{{cx, cy}, {half_length, half_width, {1.0, 0.0}}};
    std::uint8_t c = 0;
    checker.CheckPoses(&pose, 1, &c);
    return c == 1;
  };
  EXPECT_FALSE(collides(3.0, 2.0, 2.9, 1.9));
  EXPECT_TRUE(collides(3.0, 2.0, 3.0, 1.0));  // touches x = 0 and x = 6
  EXPECT_TRUE(collides(3.0, 2.0, 1.0, 2.0));  // touches y = 0 and y = 4
  EXPECT_TRUE(collides(0.5, 0.5, 0.5, 0.0));  // a segment touching the left edge
  EXPECT_FALSE(collides(0.5, 0.5, 0.49, 0.49));
  EXPECT_TRUE(collides(-0.5, 2.0, 0.0, 0.0));  // centre outside: no kernel query
  EXPECT_TRUE(collides(6.0, 2.0, 0.0, 0.0));   // centre on the boundary
  EXPECT_EQ(checker.kernel_queries(), 5u);
  // A map with no free cell: every pose collides.
  const OccupancyGrid blocked(3, 2, 1.0, CellState::kOccupied);
  KernelFootprintChecker none(blocked);
  EXPECT_TRUE(test::CheckerMatchesExactConfigurationSpace(none, blocked, FootprintStencils(0, 0, 8)));
}

PlannerOptions Footprint(double width_cells, double length_cells, int headings, FootprintCheckMode mode) {
  PlannerOptions o;
  o.footprint = RectangleFootprint{width_cells, length_cells, headings, mode};
  return o;
}

// Planning with the kernel, in either mode, gives the exact stencils' paths.
TEST(KernelFootprintChecker, PlannersFindTheExactPathsInBothModes) {
  const OccupancyGrid grid = test::RandomGrid(40, 30, 0.04, 21);
  std::mt19937 rng(4);
  std::uniform_int_distribution<int> x(0, 39), y(0, 29);
  for (const FootprintCheckMode mode : {FootprintCheckMode::kPrecomputed, FootprintCheckMode::kPerExpansion}) {
    const PlannerOptions options = Footprint(0.6, 1.4, 8, mode);
    KernelFootprintChecker kernel(grid);
    const auto exact = GridPlanner::Create(grid, Footprint(0.6, 1.4, 8, FootprintCheckMode::kPrecomputed));
    const auto on_kernel = GridPlanner::Create(grid, options, &kernel);
    int found = 0;
    for (int q = 0; q < 15; ++q) {
      const GridPose start{x(rng), y(rng)}, goal{x(rng), y(rng)};
      const PlanResult a = exact->Plan(start, goal), b = on_kernel->Plan(start, goal);
      ASSERT_EQ(a.status, b.status) << "query " << q;
      EXPECT_EQ(a.length_cells, b.length_cells);
      EXPECT_EQ(a.expanded, b.expanded);
      ASSERT_EQ(a.path.size(), b.path.size());
      for (std::size_t i = 0; i < a.path.size(); ++i) {
        EXPECT_EQ(a.path[i].x, b.path[i].x);
        EXPECT_EQ(a.path[i].y, b.path[i].y);
        EXPECT_EQ(a.path[i].heading, b.path[i].heading);
      }
      found += a.found();
    }
    EXPECT_GE(found, 5);
    EXPECT_GT(kernel.batches(), 0u);
  }
}

}  // namespace
}  // namespace rc
