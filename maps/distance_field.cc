#include "maps/distance_field.h"

#include <limits>
#include <opencv2/imgproc.hpp>

namespace rc {

DistanceField DistanceField::Build(const OccupancyGrid& grid, DistanceTarget target) {
  DistanceField field;
  field.size_x_ = grid.size_x();
  field.size_y_ = grid.size_y();
  // OpenCV measures distance to the nearest zero pixel. Rows are the grid's
  // first index so the output is already x-major. With kBlocking, a one-cell
  // frame of zeros stands for the outside of the map.
  const int pad = target == DistanceTarget::kBlocking ? 1 : 0;
  cv::Mat source(grid.size_x() + 2 * pad, grid.size_y() + 2 * pad, CV_8UC1, cv::Scalar(0));
  bool any_target = pad > 0;
  for (int ix = 0; ix < grid.size_x(); ++ix) {
    auto* row = source.ptr<std::uint8_t>(ix + pad);
    for (int iy = 0; iy < grid.size_y(); ++iy) {
      const CellState s = grid.At(ix, iy);
      bool is_target = false;
      switch (target) {
        case DistanceTarget::kBlocking: is_target = s != CellState::kFree; break;
        case DistanceTarget::kOccupied: is_target = s == CellState::kOccupied; break;
        case DistanceTarget::kFree: is_target = s == CellState::kFree; break;
      }
      row[iy + pad] = is_target ? 0 : 1;
      any_target = any_target || is_target;
    }
  }
  field.distances_m_.resize(grid.cell_count());
  if (!any_target) {
    std::fill(field.distances_m_.begin(), field.distances_m_.end(), std::numeric_limits<float>::infinity());
    return field;
  }
  cv::Mat distance_cells;
  cv::distanceTransform(source, distance_cells, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
  const float scale = static_cast<float>(grid.resolution_m());
  for (int ix = 0; ix < grid.size_x(); ++ix) {
    const float* row = distance_cells.ptr<float>(ix + pad);
    for (int iy = 0; iy < grid.size_y(); ++iy)
      field.distances_m_[static_cast<std::size_t>(ix) * grid.size_y() + iy] = row[iy + pad] * scale;
  }
  return field;
}

}  // namespace rc
