#pragma once
// Helpers shared by the maps tests: pictures of grids and their symmetry.
#include <cstddef>
#include <string>

#include "maps/occupancy_grid.h"

namespace rc::test {

// The grid as text, one line per iy from the top (largest y) down, so that
// tests can compare against a picture: '.' free, '#' occupied, '?' unknown.
inline std::string Picture(const OccupancyGrid& g) {
  std::string out;
  for (int iy = g.size_y() - 1; iy >= 0; --iy) {
    for (int ix = 0; ix < g.size_x(); ++ix) out += ".#?"[static_cast<int>(g.At(ix, iy))];
    out += '\n';
  }
  return out;
}

// Cells that differ from their image under the two mirrors and the half
// turn: a generated map for global localization must differ clearly under
// each, or two places look alike.
struct SymmetryDifferences {
  std::size_t mirror_x = 0, mirror_y = 0, half_turn = 0;
};
inline SymmetryDifferences CountSymmetryDifferences(const OccupancyGrid& g) {
  const int sx = g.size_x(), sy = g.size_y();
  SymmetryDifferences d;
  for (int ix = 0; ix < sx; ++ix)
    for (int iy = 0; iy < sy; ++iy) {
      d.mirror_x += g.At(ix, iy) != g.At(sx - 1 - ix, iy);
      d.mirror_y += g.At(ix, iy) != g.At(ix, sy - 1 - iy);
      d.half_turn += g.At(ix, iy) != g.At(sx - 1 - ix, sy - 1 - iy);
    }
  return d;
}

}  // namespace rc::test
