#include "maps/grid_connectivity.h"

#include <cstdint>
#include <vector>

namespace rc {

std::size_t CountFreeComponents(const OccupancyGrid& grid) {
  std::vector<std::uint8_t> seen(grid.cell_count(), 0);
  std::vector<std::pair<int, int>> stack;
  std::size_t components = 0;
  for (int ix = 0; ix < grid.size_x(); ++ix) {
    for (int iy = 0; iy < grid.size_y(); ++iy) {
      if (!grid.IsFree(ix, iy) || seen[grid.Index(ix, iy)]) continue;
      ++components;
      seen[grid.Index(ix, iy)] = 1;
      stack.push_back({ix, iy});
      while (!stack.empty()) {
        const auto [x, y] = stack.back();
        stack.pop_back();
        const int dx[] = {1, -1, 0, 0};
        const int dy[] = {0, 0, 1, -1};
        for (int k = 0; k < 4; ++k) {
          const int nx = x + dx[k], ny = y + dy[k];
          if (!grid.IsFree(nx, ny) || seen[grid.Index(nx, ny)]) continue;
          seen[grid.Index(nx, ny)] = 1;
          stack.push_back({nx, ny});
        }
      }
    }
  }
  return components;
}

}  // namespace rc
