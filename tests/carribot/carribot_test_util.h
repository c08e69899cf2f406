#pragma once
// Helpers for the CarriBot tests: grids from text and random grids.
#include <random>
#include <string>
#include <vector>

#include "maps/occupancy_grid.h"

namespace rc::test {

// Rows are y = 0, 1, ... (as MovingAI map lines); '.' free, '@' occupied,
// '?' unknown.
inline OccupancyGrid GridFromRows(const std::vector<std::string>& rows, double resolution_m = 1.0) {
  OccupancyGrid grid(static_cast<int>(rows.front().size()), static_cast<int>(rows.size()), resolution_m);
  for (int y = 0; y < grid.size_y(); ++y)
    for (int x = 0; x < grid.size_x(); ++x)
      grid.Set(x, y,
               rows[y][x] == '.'   ? CellState::kFree
               : rows[y][x] == '@' ? CellState::kOccupied
                                   : CellState::kUnknown);
  return grid;
}

// Each cell blocked with probability `blocked` (seeded, reproducible).
inline OccupancyGrid RandomGrid(int size_x, int size_y, double blocked, unsigned seed) {
  std::mt19937 rng(seed);
  std::bernoulli_distribution is_blocked(blocked);
  OccupancyGrid grid(size_x, size_y, 1.0);
  for (int x = 0; x < size_x; ++x)
    for (int y = 0; y < size_y; ++y) grid.Set(x, y, is_blocked(rng) ? CellState::kOccupied : CellState::kFree);
  return grid;
}

}  // namespace rc::test
