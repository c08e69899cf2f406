#include "workloads/carribot/octile_grid_space.h"

#include <stdexcept>

namespace rc {

OctileGridSpace::OctileGridSpace(const OccupancyGrid& grid)
    : size_x_(grid.size_x()), size_y_(grid.size_y()), padded_y_(grid.size_y() + 2) {
  const std::size_t padded_cells = static_cast<std::size_t>(size_x_ + 2) * static_cast<std::size_t>(padded_y_);
  if (padded_cells >= 0xFFFFFFF0u) throw std::invalid_argument("OctileGridSpace: grid too large for 32-bit states");
  passable_.assign(padded_cells, 0);
  for (int ix = 0; ix < size_x_; ++ix)
    for (int iy = 0; iy < size_y_; ++iy) passable_[StateOf(ix, iy)] = grid.IsFree(ix, iy) ? 1 : 0;
  for (int d = 0; d < 8; ++d)
    offset_[d] = static_cast<std::int64_t>(kOctileSteps[d].dx) * padded_y_ + kOctileSteps[d].dy;
}

void OctileGridSpace::SetGoal(int gx, int gy) {
  goal_x_ = gx;
  goal_y_ = gy;
  goal_ = StateOf(gx, gy);
  collision_queries_ = 0;
}

}  // namespace rc
