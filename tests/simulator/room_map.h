#pragma once
// The simulator tests' map, and an exact clearance check that is independent
// of the planner's distance-field inflation.
#include <algorithm>
#include <cmath>
#include <limits>

#include "maps/occupancy_grid.h"

namespace rc::test {

// Marks the cells whose centres fall inside [x0, x1) x [y0, y1) (m).
inline void FillRect(OccupancyGrid& grid, double x0, double y0, double x1, double y1, CellState state) {
  const double r = grid.resolution_m();
  for (int ix = 0; ix < grid.size_x(); ++ix)
    for (int iy = 0; iy < grid.size_y(); ++iy) {
      const double cx = (ix + 0.5) * r, cy = (iy + 0.5) * r;
      if (cx >= x0 && cx < x1 && cy >= y0 && cy < y1) grid.Set(ix, iy, state);
    }
}

// Door in the dividing wall (m): y in [kDoorY0, kDoorY1).
inline constexpr double kDoorY0 = 3.5, kDoorY1 = 4.5;
inline constexpr double kWallX0 = 5.0, kWallX1 = 5.1;

// 10 m x 8 m at 0.05 m (200 x 160 cells): 0.1 m outer walls, a dividing
// wall at x in [5.0, 5.1) with a 1 m door, a 1 m box in the left room and an
// unknown patch (which also blocks) in the right room.
inline OccupancyGrid MakeRoomWithDoor() {
  OccupancyGrid grid(200, 160, 0.05, CellState::kFree);
  FillRect(grid, 0.0, 0.0, 10.0, 0.1, CellState::kOccupied);
  FillRect(grid, 0.0, 7.9, 10.0, 8.0, CellState::kOccupied);
  FillRect(grid, 0.0, 0.0, 0.1, 8.0, CellState::kOccupied);
  FillRect(grid, 9.9, 0.0, 10.0, 8.0, CellState::kOccupied);
  FillRect(grid, kWallX0, 0.0, kWallX1, kDoorY0, CellState::kOccupied);
  FillRect(grid, kWallX0, kDoorY1, kWallX1, 8.0, CellState::kOccupied);
  FillRect(grid, 2.0, 5.0, 3.0, 6.0, CellState::kOccupied);
  FillRect(grid, 7.0, 1.5, 8.0, 2.5, CellState::kUnknown);
  return grid;
}

// Exact distance (m) from a point to the nearest non-free cell (as a
// square) or the map border, searched up to `search_m`; returns search_m if
// nothing is that close.
inline double ClearanceToBlocking(const OccupancyGrid& grid, double x, double y, double search_m) {
  double best = std::min({search_m, x, y, grid.extent_x_m() - x, grid.extent_y_m() - y});
  const double r = grid.resolution_m();
  const int ix0 = std::max(0, static_cast<int>(std::floor((x - search_m) / r)));
  const int iy0 = std::max(0, static_cast<int>(std::floor((y - search_m) / r)));
  const int ix1 = std::min(grid.size_x() - 1, static_cast<int>(std::floor((x + search_m) / r)));
  const int iy1 = std::min(grid.size_y() - 1, static_cast<int>(std::floor((y + search_m) / r)));
  for (int ix = ix0; ix <= ix1; ++ix)
    for (int iy = iy0; iy <= iy1; ++iy) {
      if (grid.At(ix, iy) == CellState::kFree) continue;
      const double dx = std::max({ix * r - x, 0.0, x - (ix + 1) * r});
      const double dy = std::max({iy * r - y, 0.0, y - (iy + 1) * r});
      best = std::min(best, std::hypot(dx, dy));
    }
  return best;
}

}  // namespace rc::test
