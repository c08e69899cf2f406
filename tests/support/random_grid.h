#pragma once
// A seeded random occupancy grid for ray-casting tests: each cell is
// occupied with probability occupied_fraction, unknown with 0.2 times that,
// free otherwise.
#include <cstdint>

#include "common/random_stream.h"
#include "maps/occupancy_grid.h"

namespace rc::test {

inline OccupancyGrid RandomGrid(int sx, int sy, double resolution_m, double occupied_fraction, std::uint64_t seed) {
  OccupancyGrid g(sx, sy, resolution_m);
  RandomStream s(seed, StreamPurpose::kTest, 0, 0);
  for (int x = 0; x < sx; ++x)
    for (int y = 0; y < sy; ++y) {
      const double u = s.Uniform();
      g.Set(x, y,
            u < occupied_fraction ? CellState::kOccupied
                                  : (u < occupied_fraction * 1.2 ? CellState::kUnknown : CellState::kFree));
    }
  return g;
}

}  // namespace rc::test
