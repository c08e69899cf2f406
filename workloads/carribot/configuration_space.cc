#include "workloads/carribot/configuration_space.h"

#include <algorithm>
#include <stdexcept>

#include "workloads/carribot/cell_stencil.h"

namespace rc {

ConfigurationSpace::ConfigurationSpace(int size_x, int size_y, int heading_count)
    : size_x_(size_x),
      size_y_(size_y),
      heading_count_(heading_count),
      free_(static_cast<std::size_t>(size_x) * size_y * heading_count, 0) {}

ConfigurationSpace ConfigurationSpace::FromStencils(const OccupancyGrid& grid, const FootprintStencils& stencils) {
  ConfigurationSpace space(grid.size_x(), grid.size_y(), stencils.heading_count());
  const ColumnBlockIndex blocks(grid);
  const int n = stencils.heading_count();
  for (int h = 0; h < n; ++h) {
    const CellStencil& stencil = stencils.footprint(h);
    for (int ix = 0; ix < grid.size_x(); ++ix)
      for (int iy = 0; iy < grid.size_y(); ++iy)
        space.free_[grid.Index(ix, iy) * n + h] = blocks.StencilIsFree(stencil, ix, iy) ? 1 : 0;
  }
  return space;
}

ConfigurationSpace ConfigurationSpace::FromChecker(const OccupancyGrid& grid, const FootprintStencils& stencils,
                                                   FootprintChecker& checker, std::size_t max_batch) {
  if (max_batch == 0) throw std::invalid_argument("ConfigurationSpace::FromChecker: max_batch must be >= 1");
  ConfigurationSpace space(grid.size_x(), grid.size_y(), stencils.heading_count());
  const int n = stencils.heading_count();
  // States in (heading, x, y) order: consecutive queries are neighbouring
  // cells at one heading, so a batch's queries walk the tree alike.
  const std::size_t cells = grid.cell_count(), total = cells * static_cast<std::size_t>(n);
  std::vector<FootprintPose> poses;
  std::vector<std::uint8_t> collides;
  for (std::size_t first = 0; first < total; first += max_batch) {
    const std::size_t count = std::min(max_batch, total - first);
    poses.resize(count);
    collides.resize(count);
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t cell = (first + k) % cells;
      const int h = static_cast<int>((first + k) / cells);
      poses[k] = stencils.PoseAt(static_cast<int>(cell / grid.size_y()), static_cast<int>(cell % grid.size_y()), h);
    }
    checker.CheckPoses(poses.data(), count, collides.data());
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t cell = (first + k) % cells;
      const std::size_t h = (first + k) / cells;
      space.free_[cell * n + h] = collides[k] ? 0 : 1;
    }
  }
  return space;
}

std::size_t ConfigurationSpace::CountFree() const {
  return static_cast<std::size_t>(std::count(free_.begin(), free_.end(), std::uint8_t{1}));
}

}  // namespace rc
