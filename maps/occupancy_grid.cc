#include "maps/occupancy_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace rc {

OccupancyGrid::OccupancyGrid(int size_x, int size_y, double resolution_m, CellState fill)
    : size_x_(size_x), size_y_(size_y), resolution_m_(resolution_m) {
  if (size_x <= 0 || size_y <= 0)
    throw std::invalid_argument("grid size must be positive, got " + std::to_string(size_x) + " x " +
                                std::to_string(size_y));
  if (!(resolution_m > 0.0) || !std::isfinite(resolution_m))
    throw std::invalid_argument("grid resolution must be a positive number of metres");
  // Cell indices are stored as 32-bit values in free-cell lists and traces.
  if (static_cast<double>(size_x) * size_y > std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument("grid has more than 2^32 cells");
  cells_.assign(static_cast<std::size_t>(size_x) * size_y, fill);
}

bool OccupancyGrid::IsFreePoint(double x_m, double y_m) const {
  if (!(x_m >= 0.0) || !(y_m >= 0.0)) return false;
  const double fx = std::floor(x_m / resolution_m_);
  const double fy = std::floor(y_m / resolution_m_);
  if (fx >= size_x_ || fy >= size_y_) return false;
  return At(static_cast<int>(fx), static_cast<int>(fy)) == CellState::kFree;
}

std::vector<std::uint32_t> OccupancyGrid::FreeCellIndices() const {
  std::vector<std::uint32_t> out;
  for (std::size_t i = 0; i < cells_.size(); ++i)
    if (cells_[i] == CellState::kFree) out.push_back(static_cast<std::uint32_t>(i));
  return out;
}

std::size_t OccupancyGrid::CountCells(CellState s) const {
  return static_cast<std::size_t>(std::count(cells_.begin(), cells_.end(), s));
}

}  // namespace rc
