// Footprint stencils and configuration spaces: the stencil shortcut equals a
// pose-by-pose exact check on every cell and heading, and both equal a
// brute-force polygon clipping of the footprint against the map.
#include "workloads/carribot/configuration_space.h"

#include <gtest/gtest.h>

#include "carribot/brute_force_geometry.h"
#include "carribot/carribot_test_util.h"
#include "carribot/footprint_checker_conformance.h"
#include "maps/movingai_map_loader.h"
#include "support/test_data.h"
#include "workloads/carribot/octile_steps.h"
#include "workloads/carribot/rasterized_footprint_checker.h"

namespace rc {
namespace {

struct Shape {
  double length_cells, width_cells;
};
// Integer and half-integer sizes put edges exactly on cell boundaries at
// quarter-turn headings, where touching must be decided exactly.
const Shape kShapes[] = {{0, 0}, {1, 1}, {3, 1}, {2.4, 0.9}, {5, 2}, {10, 4}, {1.7, 3.3}};

TEST(FootprintStencils, PointFootprintGivesTheOctileRules) {
  const FootprintStencils s(0.0, 0.0, 8);
  for (int h = 0; h < 8; ++h) {
    EXPECT_EQ(s.footprint(h).Offsets(), (std::vector<CellOffset>{{0, 0}}));
    EXPECT_TRUE(s.rotation_extra(h).empty());
    for (int d = 0; d < 8; ++d) {
      if (!IsDiagonalStep(d)) {
        EXPECT_TRUE(s.translation_extra(h, d).empty());
        continue;
      }
      const GridStep step = kOctileSteps[d];
      EXPECT_EQ(s.translation_extra(h, d).Offsets(), CellStencil({{step.dx, 0}, {0, step.dy}}).Offsets());
    }
  }
}

TEST(FootprintStencils, AxisAlignedSizesTouchExactly) {
  const FootprintStencils unit(1.0, 1.0, 8);
  EXPECT_EQ(unit.footprint(0).cell_count(), 9u);  // touches all eight neighbours
  const FootprintStencils bar(3.0, 1.0, 16);
  EXPECT_EQ(bar.footprint(0).cell_count(), 15u);  // 5 columns x 3 rows
  EXPECT_EQ(bar.footprint(4).cell_count(), 15u);  // 3 columns x 5 rows
  EXPECT_TRUE(bar.footprint(4).Contains({1, 2}));
  EXPECT_FALSE(bar.footprint(4).Contains({2, 1}));
}

TEST(FootprintStencils, FootprintsEqualBruteForceClipping) {
  for (const Shape& shape : kShapes) {
    for (const int n : {8, 16}) {
      const FootprintStencils s(shape.length_cells, shape.width_cells, n);
      for (int h = 0; h < n; ++h) {
        std::vector<CellOffset> expected;
        const test::Polygon poly =
            test::BoxPolygon({0, 0}, shape.length_cells / 2, shape.width_cells / 2, HeadingAxis(h, n));
        for (int dx = -8; dx <= 8; ++dx)
          for (int dy = -8; dy <= 8; ++dy)
            if (test::PolygonTouchesSquare(poly, {dx - 0.5, dy - 0.5}, {dx + 0.5, dy + 0.5}))
              expected.push_back({dx, dy});
        EXPECT_EQ(s.footprint(h).Offsets(), CellStencil(expected).Offsets())
            << shape.length_cells << " x " << shape.width_cells << " heading " << h << "/" << n;
      }
    }
  }
}

TEST(FootprintStencils, MotionExtrasAreDisjointFromTheEndFootprints) {
  const FootprintStencils s(5.0, 2.0, 16);
  for (int h = 0; h < 16; ++h) {
    for (int d = 0; d < 8; ++d) {
      const CellStencil& extra = s.translation_extra(h, d);
      const GridStep step = kOctileSteps[d];
      for (const CellOffset o : extra.Offsets()) {
        EXPECT_FALSE(s.footprint(h).Contains(o));
        EXPECT_FALSE(s.footprint(h).Contains({o.dx - step.dx, o.dy - step.dy}));
      }
      EXPECT_EQ(s.TranslationSweep(h, d).cell_count(),
                extra.cell_count() + s.footprint(h).Union(s.footprint(h).Shifted(step.dx, step.dy)).cell_count());
    }
    const int next = (h + 1) % 16;
    const CellStencil ends = s.footprint(h).Union(s.footprint(next));
    EXPECT_EQ(s.RotationSweep(h).cell_count(), s.rotation_extra(h).cell_count() + ends.cell_count());
    EXPECT_TRUE(s.RotationSweep(h).Minus(ends).Offsets() == s.rotation_extra(h).Offsets());
  }
  // A long bar turning by 45 degrees sweeps a fan well beyond both ends.
  const FootprintStencils bar(10.0, 1.0, 8);
  for (int h = 0; h < 8; ++h) EXPECT_GE(bar.rotation_extra(h).cell_count(), 4u) << "heading " << h;
}

TEST(ConfigurationSpace, RasterizedCheckerMatchesStencilsOnRandomMaps) {
  for (unsigned seed = 1; seed <= 4; ++seed) {
    const OccupancyGrid grid = test::RandomGrid(23, 17, 0.08 * seed, seed);
    for (const Shape& shape : kShapes) {
      for (const int n : {8, 16}) {
        const FootprintStencils stencils(shape.length_cells, shape.width_cells, n);
        RasterizedFootprintChecker checker(grid);
        EXPECT_TRUE(test::CheckerMatchesExactConfigurationSpace(checker, grid, stencils))
            << "seed " << seed << ", " << shape.length_cells << " x " << shape.width_cells << ", " << n;
      }
    }
  }
}

TEST(ConfigurationSpace, RasterizedCheckerMatchesStencilsOnDen312d) {
  RC_REQUIRE_SHARED_DATA("movingai/den312d.map");
  const OccupancyGrid grid = LoadMovingAiMap(test::SharedDataPath("movingai/den312d.map"));
  for (const Shape& shape : {Shape{3, 1}, Shape{2.4, 0.9}, Shape{6, 3}}) {
    const FootprintStencils stencils(shape.length_cells, shape.width_cells, 16);
    RasterizedFootprintChecker checker(grid);
    EXPECT_TRUE(test::CheckerMatchesExactConfigurationSpace(checker, grid, stencils));
    EXPECT_EQ(checker.poses_checked(), grid.cell_count() * 16);
  }
}

// Off-lattice poses too: the checker against clipping over the whole map.
TEST(RasterizedFootprintChecker, AgreesWithBruteForceOnRandomPoses) {
  const OccupancyGrid grid = test::RandomGrid(12, 9, 0.1, 5);
  RasterizedFootprintChecker checker(grid);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> x(-1.0, 13.0), y(-1.0, 10.0), angle(0, 6.283185307179586), extent(0, 1.5);
  int collisions = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const double a = angle(rng);
    const FootprintPose pose{{x(rng), y(rng)}, {extent(rng), extent(rng), {std::cos(a), std::sin(a)}}};
    const test::Polygon poly = test::BoxPolygon(pose.center, pose.box.half_length, pose.box.half_width, pose.box.axis);
    bool expected = false;
    for (int ix = -6; ix < grid.size_x() + 6 && !expected; ++ix)
      for (int iy = -6; iy < grid.size_y() + 6 && !expected; ++iy)
        if (!grid.IsFree(ix, iy))  // the outside of the map counts as blocked
          expected = test::PolygonTouchesSquare(poly, {double(ix), double(iy)}, {ix + 1.0, iy + 1.0});
    ASSERT_EQ(checker.Collides(pose), expected) << "trial " << trial;
    collisions += expected;
  }
  EXPECT_GT(collisions, 300);
  EXPECT_LT(collisions, 2700);
}

}  // namespace
}  // namespace rc
