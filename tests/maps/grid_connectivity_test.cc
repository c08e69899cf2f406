#include "maps/grid_connectivity.h"

#include <gtest/gtest.h>

namespace rc {
namespace {

TEST(GridConnectivity, CountsFourConnectedFreeRegions) {
  OccupancyGrid g(5, 3, 1.0, CellState::kFree);
  EXPECT_EQ(CountFreeComponents(g), 1u);
  for (int iy = 0; iy < 3; ++iy) g.Set(2, iy, CellState::kOccupied);  // a wall across x = 2
  EXPECT_EQ(CountFreeComponents(g), 2u);
  g.Set(2, 1, CellState::kUnknown);  // unknown does not connect either
  EXPECT_EQ(CountFreeComponents(g), 2u);
  g.Set(2, 1, CellState::kFree);  // a door
  EXPECT_EQ(CountFreeComponents(g), 1u);
}

TEST(GridConnectivity, DiagonalNeighboursAreNotConnected) {
  OccupancyGrid g(2, 2, 1.0, CellState::kOccupied);
  g.Set(0, 0, CellState::kFree);
  g.Set(1, 1, CellState::kFree);
  EXPECT_EQ(CountFreeComponents(g), 2u);
}

TEST(GridConnectivity, NoFreeCellMeansNoComponent) {
  EXPECT_EQ(CountFreeComponents(OccupancyGrid(3, 3, 1.0, CellState::kUnknown)), 0u);
}

}  // namespace
}  // namespace rc
