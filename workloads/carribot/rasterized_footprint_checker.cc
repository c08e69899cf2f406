#include "workloads/carribot/rasterized_footprint_checker.h"

#include <cmath>

namespace rc {

RasterizedFootprintChecker::RasterizedFootprintChecker(const OccupancyGrid& grid)
    : size_x_(grid.size_x()), size_y_(grid.size_y()), free_(grid.cell_count()) {
  for (std::size_t i = 0; i < free_.size(); ++i) free_[i] = grid.cells()[i] == CellState::kFree ? 1 : 0;
}

bool RasterizedFootprintChecker::Collides(const FootprintPose& pose) {
  ++poses_checked_;
  const Vec2 e = BoundingHalfExtents(pose.box);
  const Vec2 c = pose.center;
  // Cells whose closed square can touch the closed bounding box; the SAT
  // decides the rest.
  const int ix_lo = static_cast<int>(std::ceil(c.x - e.x)) - 1, ix_hi = static_cast<int>(std::floor(c.x + e.x));
  const int iy_lo = static_cast<int>(std::ceil(c.y - e.y)) - 1, iy_hi = static_cast<int>(std::floor(c.y + e.y));
  for (int ix = ix_lo; ix <= ix_hi; ++ix) {
    for (int iy = iy_lo; iy <= iy_hi; ++iy) {
      if (!IsBlocked(ix, iy)) continue;
      ++cell_tests_;
      // Relative to the centre, so that lattice poses give exactly the
      // numbers of OffsetCellSquare (footprint_geometry.h).
      const CellSquare square{{ix - c.x, iy - c.y}, {(ix + 1) - c.x, (iy + 1) - c.y}};
      if (BoxTouchesSquare(pose.box, square)) return true;
    }
  }
  return false;
}

void RasterizedFootprintChecker::CheckPoses(const FootprintPose* poses, std::size_t count, std::uint8_t* collides) {
  for (std::size_t i = 0; i < count; ++i) collides[i] = Collides(poses[i]) ? 1 : 0;
}

}  // namespace rc
