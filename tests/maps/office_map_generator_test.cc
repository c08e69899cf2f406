#include "maps/office_map_generator.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <deque>

#include "common/input_error.h"
#include "map_test_util.h"
#include "maps/grid_connectivity.h"

namespace rc {
namespace {

// Free cells reached from the first free cell by a breadth-first search,
// written independently of CountFreeComponents.
std::size_t ReachableFromFirstFree(const OccupancyGrid& g) {
  const auto free = g.FreeCellIndices();
  if (free.empty()) return 0;
  std::vector<bool> seen(g.cell_count(), false);
  std::deque<std::uint32_t> queue{free.front()};
  seen[free.front()] = true;
  std::size_t reached = 0;
  while (!queue.empty()) {
    const std::uint32_t i = queue.front();
    queue.pop_front();
    ++reached;
    const int ix = static_cast<int>(i / g.size_y()), iy = static_cast<int>(i % g.size_y());
    const int nx[] = {ix + 1, ix - 1, ix, ix};
    const int ny[] = {iy, iy, iy + 1, iy - 1};
    for (int k = 0; k < 4; ++k) {
      if (!g.IsFree(nx[k], ny[k])) continue;
      const auto j = static_cast<std::uint32_t>(g.Index(nx[k], ny[k]));
      if (!seen[j]) seen[j] = true, queue.push_back(j);
    }
  }
  return reached;
}

TEST(OfficeMapGenerator, DefaultIs20By15MetresAtFiveCentimetres) {
  const OccupancyGrid g = GenerateOfficeMap();
  EXPECT_EQ(g.size_x(), 400);
  EXPECT_EQ(g.size_y(), 300);
  EXPECT_DOUBLE_EQ(g.resolution_m(), 0.05);
  EXPECT_EQ(g.CountCells(CellState::kUnknown), 0u);
  // Mostly open, but with real structure.
  const double free_fraction = static_cast<double>(g.CountCells(CellState::kFree)) / g.cell_count();
  EXPECT_GT(free_fraction, 0.6);
  EXPECT_LT(free_fraction, 0.9);
}

// 0.03 does not divide 20 m: the border must still be closed there too.
TEST(OfficeMapGenerator, EveryFreeCellReachesEveryOtherAndTheBorderIsClosed) {
  for (double resolution : {0.05, 0.1, 0.03}) {
    for (std::uint64_t seed = 1; seed <= 8; ++seed) {
      SCOPED_TRACE("resolution " + std::to_string(resolution) + ", seed " + std::to_string(seed));
      OfficeMapOptions o;
      o.resolution_m = resolution;
      o.seed = seed;
      const OccupancyGrid g = GenerateOfficeMap(o);
      EXPECT_EQ(ReachableFromFirstFree(g), g.CountCells(CellState::kFree));
      EXPECT_EQ(CountFreeComponents(g), 1u);
      std::size_t free_border_cells = 0;
      for (int ix = 0; ix < g.size_x(); ++ix) free_border_cells += g.IsFree(ix, 0) + g.IsFree(ix, g.size_y() - 1);
      for (int iy = 0; iy < g.size_y(); ++iy) free_border_cells += g.IsFree(0, iy) + g.IsFree(g.size_x() - 1, iy);
      EXPECT_EQ(free_border_cells, 0u);
    }
  }
}

TEST(OfficeMapGenerator, DoorsAreOpenAndAtLeastOneMetreWide) {
  for (double resolution : {0.05, 0.1}) {
    OfficeMapOptions o;
    o.resolution_m = resolution;
    const OccupancyGrid g = GenerateOfficeMap(o);
    for (const MetricRect& door : OfficeDoorOpenings()) {
      int cells_x = 0, cells_y = 0;
      for (int ix = 0; ix < g.size_x(); ++ix) {
        const double cx = (ix + 0.5) * resolution;
        if (cx < door.x0_m || cx >= door.x1_m) continue;
        ++cells_x;
        cells_y = 0;
        for (int iy = 0; iy < g.size_y(); ++iy) {
          const double cy = (iy + 0.5) * resolution;
          if (cy < door.y0_m || cy >= door.y1_m) continue;
          ++cells_y;
          EXPECT_TRUE(g.IsFree(ix, iy)) << "door at " << door.x0_m << "," << door.y0_m;
        }
      }
      const double opening_m = std::max(cells_x, cells_y) * resolution;
      EXPECT_GE(opening_m, 1.0 - 1e-9) << "door at " << door.x0_m << "," << door.y0_m;
    }
  }
}

TEST(OfficeMapGenerator, SameSeedSameMapOtherSeedOtherFurniture) {
  OfficeMapOptions a, b;
  a.seed = b.seed = 42;
  EXPECT_TRUE(GenerateOfficeMap(a).cells() == GenerateOfficeMap(b).cells());
  b.seed = 43;
  EXPECT_FALSE(GenerateOfficeMap(a).cells() == GenerateOfficeMap(b).cells());
}

// Global localization needs a map that no mirror or half-turn maps onto
// itself; require a clear difference, not just a few cells.
TEST(OfficeMapGenerator, IsNotSymmetric) {
  const OccupancyGrid g = GenerateOfficeMap();
  const test::SymmetryDifferences d = test::CountSymmetryDifferences(g);
  const std::size_t minimum = g.cell_count() / 20;  // 5 % of the cells
  EXPECT_GT(d.mirror_x, minimum);
  EXPECT_GT(d.mirror_y, minimum);
  EXPECT_GT(d.half_turn, minimum);
}

TEST(OfficeMapGenerator, ResolutionOutsideItsRangeIsAUsageError) {
  std::string error;
  OfficeMapOptions o;
  EXPECT_TRUE(o.IsValid(&error));
  for (double bad : {0.0, -0.05, 0.011, 0.2, std::nan("")}) {
    o.resolution_m = bad;
    EXPECT_FALSE(o.IsValid(&error)) << bad;
    EXPECT_THROW(GenerateOfficeMap(o), UsageError) << bad;
  }
}

}  // namespace
}  // namespace rc
