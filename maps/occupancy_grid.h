#pragma once
// A 2D occupancy grid with a compact one-byte cell and an explicit frame.
//
// Frame (used by every loader, trace and output of rcbench):
//   - the map frame's origin is the outer corner of cell (0, 0);
//   - x runs along the first index ix, y along the second index iy;
//   - cell (ix, iy) covers [ix*r, (ix+1)*r) x [iy*r, (iy+1)*r), r = resolution;
//   - storage is x-major: index = ix * size_y + iy (as wean.dat's rows and
//     the RoboGPU artifact's x * sizeY + y).
// Loaders map their format's own value convention to the three states below
// and say so in their header; nothing downstream sees raw probabilities.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace rc {

enum class CellState : std::uint8_t {
  kFree = 0,
  kOccupied = 1,
  kUnknown = 2,
};

class OccupancyGrid {
 public:
  OccupancyGrid() = default;
  // Throws std::invalid_argument for a non-positive size or resolution.
  OccupancyGrid(int size_x, int size_y, double resolution_m, CellState fill = CellState::kFree);

  int size_x() const { return size_x_; }
  int size_y() const { return size_y_; }
  double resolution_m() const { return resolution_m_; }
  double extent_x_m() const { return size_x_ * resolution_m_; }
  double extent_y_m() const { return size_y_ * resolution_m_; }
  std::size_t cell_count() const { return cells_.size(); }

  bool Contains(int ix, int iy) const { return ix >= 0 && iy >= 0 && ix < size_x_ && iy < size_y_; }
  std::size_t Index(int ix, int iy) const {
    return static_cast<std::size_t>(ix) * static_cast<std::size_t>(size_y_) + static_cast<std::size_t>(iy);
  }
  CellState At(int ix, int iy) const { return cells_[Index(ix, iy)]; }
  void Set(int ix, int iy, CellState s) { cells_[Index(ix, iy)] = s; }
  bool IsFree(int ix, int iy) const { return Contains(ix, iy) && At(ix, iy) == CellState::kFree; }
  // True for a point (m) inside a free cell.
  bool IsFreePoint(double x_m, double y_m) const;

  const std::vector<CellState>& cells() const { return cells_; }
  std::vector<CellState>& mutable_cells() { return cells_; }
  // Flat indices of every free cell, in storage order.
  std::vector<std::uint32_t> FreeCellIndices() const;
  std::size_t CountCells(CellState s) const;

 private:
  int size_x_ = 0;
  int size_y_ = 0;
  double resolution_m_ = 0.0;
  std::vector<CellState> cells_;
};

}  // namespace rc
