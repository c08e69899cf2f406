#include "maps/hall_map_generator.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "common/input_error.h"
#include "map_test_util.h"
#include "maps/grid_connectivity.h"

namespace rc {
namespace {

// The longest run of free cells along any row or column (cells).
int LongestFreeRun(const OccupancyGrid& g) {
  int best = 0;
  for (int ix = 0; ix < g.size_x(); ++ix)
    for (int iy = 0, run = 0; iy < g.size_y(); ++iy) best = std::max(best, run = g.IsFree(ix, iy) ? run + 1 : 0);
  for (int iy = 0; iy < g.size_y(); ++iy)
    for (int ix = 0, run = 0; ix < g.size_x(); ++ix) best = std::max(best, run = g.IsFree(ix, iy) ? run + 1 : 0);
  return best;
}

TEST(HallMapGenerator, DefaultIs60By40MetresAtTenCentimetresWithLongSightLines) {
  const OccupancyGrid g = GenerateHallMap();
  EXPECT_EQ(g.size_x(), 600);
  EXPECT_EQ(g.size_y(), 400);
  EXPECT_DOUBLE_EQ(g.resolution_m(), 0.1);
  EXPECT_EQ(g.CountCells(CellState::kUnknown), 0u);
  // What the scene is for: rays of tens of metres (the office's are < 20 m).
  EXPECT_GE(LongestFreeRun(g) * g.resolution_m(), 30.0);
  const double free_fraction = static_cast<double>(g.CountCells(CellState::kFree)) / g.cell_count();
  EXPECT_GT(free_fraction, 0.85);
}

// 0.07 does not divide 60 m: the border must still be closed there too.
TEST(HallMapGenerator, EveryFreeCellReachesEveryOtherAndTheBorderIsClosed) {
  for (double resolution : {0.1, 0.2, 0.07}) {
    for (std::uint64_t seed = 1; seed <= 4; ++seed) {
      SCOPED_TRACE("resolution " + std::to_string(resolution) + ", seed " + std::to_string(seed));
      HallMapOptions o;
      o.resolution_m = resolution;
      o.seed = seed;
      const OccupancyGrid g = GenerateHallMap(o);
      EXPECT_EQ(CountFreeComponents(g), 1u);
      std::size_t free_border_cells = 0;
      for (int ix = 0; ix < g.size_x(); ++ix) free_border_cells += g.IsFree(ix, 0) + g.IsFree(ix, g.size_y() - 1);
      for (int iy = 0; iy < g.size_y(); ++iy) free_border_cells += g.IsFree(0, iy) + g.IsFree(g.size_x() - 1, iy);
      EXPECT_EQ(free_border_cells, 0u);
    }
  }
}

TEST(HallMapGenerator, SameSeedSameMapOtherSeedOtherPallets) {
  HallMapOptions a, b;
  a.seed = b.seed = 7;
  EXPECT_TRUE(GenerateHallMap(a).cells() == GenerateHallMap(b).cells());
  b.seed = 8;
  EXPECT_FALSE(GenerateHallMap(a).cells() == GenerateHallMap(b).cells());
}

// Global localization needs a map that no mirror or half-turn maps onto
// itself: the racks sit in the west quarter only.
TEST(HallMapGenerator, IsNotSymmetric) {
  const OccupancyGrid g = GenerateHallMap();
  const test::SymmetryDifferences d = test::CountSymmetryDifferences(g);
  const std::size_t minimum = g.cell_count() / 100;  // 1 % of the cells
  EXPECT_GT(d.mirror_x, minimum);
  EXPECT_GT(d.mirror_y, minimum / 4);
  EXPECT_GT(d.half_turn, minimum);
}

TEST(HallMapGenerator, ResolutionOutsideItsRangeIsAUsageError) {
  std::string error;
  HallMapOptions o;
  EXPECT_TRUE(o.IsValid(&error));
  for (double bad : {0.0, -0.1, 0.049, 0.21, std::nan("")}) {
    o.resolution_m = bad;
    EXPECT_FALSE(o.IsValid(&error)) << bad;
    EXPECT_THROW(GenerateHallMap(o), UsageError) << bad;
  }
}

}  // namespace
}  // namespace rc
