#pragma once
// Euclidean distance (m) from every cell centre to the nearest target cell
// centre, computed with OpenCV's exact distance transform
// (cv::distanceTransform, DIST_L2, DIST_MASK_PRECISE).
//
// Built only on demand: by the `rm` ray caster (targets = every cell that
// stops a ray, with the outside of the map counted as blocking) and by the
// likelihood-field sensor model (targets = occupied cells only, as in AMCL;
// plus free cells, for the depth of an end point inside a wall).
// Memory: 4 bytes per cell. Build time: linear in the cell count.
#include <cstddef>
#include <vector>

#include "maps/occupancy_grid.h"

namespace rc {

enum class DistanceTarget {
  kBlocking,  // occupied, unknown, and the outside of the map (ray stoppers)
  kOccupied,  // occupied cells only
  kFree,      // free cells only (depth inside walls, for a signed distance)
};

class DistanceField {
 public:
  DistanceField() = default;
  static DistanceField Build(const OccupancyGrid& grid, DistanceTarget target);

  int size_x() const { return size_x_; }
  int size_y() const { return size_y_; }
  // Distance in metres at cell (ix, iy), x-major like the grid. If the grid
  // has no target cell at all, every value is +inf (kOccupied and kFree;
  // with kBlocking the map border is always a target).
  float At(int ix, int iy) const { return distances_m_[static_cast<std::size_t>(ix) * size_y_ + iy]; }
  const std::vector<float>& values() const { return distances_m_; }
  std::size_t memory_bytes() const { return distances_m_.size() * sizeof(float); }

 private:
  int size_x_ = 0;
  int size_y_ = 0;
  std::vector<float> distances_m_;
};

}  // namespace rc
