#include "workloads/carribot/configuration_space.h"

#include <algorithm>

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
                                                   FootprintChecker& checker) {
  ConfigurationSpace space(grid.size_x(), grid.size_y(), stencils.heading_count());
  const int n = stencils.heading_count();
  std::vector<FootprintPose> poses(grid.size_y());
  std::vector<std::uint8_t> collides(grid.size_y());
  for (int h = 0; h < n; ++h) {
    for (int ix = 0; ix < grid.size_x(); ++ix) {
      for (int iy = 0; iy < grid.size_y(); ++iy) poses[iy] = stencils.PoseAt(ix, iy, h);
      checker.CheckPoses(poses.data(), poses.size(), collides.data());
      for (int iy = 0; iy < grid.size_y(); ++iy) space.free_[grid.Index(ix, iy) * n + h] = collides[iy] ? 0 : 1;
    }
  }
  return space;
}

std::size_t ConfigurationSpace::CountFree() const {
  return static_cast<std::size_t>(std::count(free_.begin(), free_.end(), std::uint8_t{1}));
}

}  // namespace rc
