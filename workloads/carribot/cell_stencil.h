#pragma once
// A set of cell offsets (dx, dy) relative to the cell that holds a footprint's
// centre, stored as column runs: for each dx, maximal intervals dy_lo..dy_hi.
// A rasterized convex region has one run per column, so checking a stencil
// at a cell costs one lookup per column with a ColumnBlockIndex.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "maps/occupancy_grid.h"

namespace rc {

struct CellOffset {
  int dx;
  int dy;
  bool operator==(const CellOffset& o) const { return dx == o.dx && dy == o.dy; }
  bool operator<(const CellOffset& o) const { return dx != o.dx ? dx < o.dx : dy < o.dy; }
};

struct CellRun {
  int dx;
  int dy_lo;
  int dy_hi;  // inclusive
};

class CellStencil {
 public:
  CellStencil() = default;
  // Any order; duplicates are merged.
  explicit CellStencil(std::vector<CellOffset> offsets);

  const std::vector<CellRun>& runs() const { return runs_; }
  std::size_t cell_count() const { return cell_count_; }
  bool empty() const { return cell_count_ == 0; }
  bool Contains(CellOffset o) const;
  std::vector<CellOffset> Offsets() const;  // sorted by dx, then dy

  CellStencil Shifted(int dx, int dy) const;
  CellStencil Minus(const CellStencil& other) const;
  CellStencil Union(const CellStencil& other) const;

 private:
  std::vector<CellRun> runs_;
  std::size_t cell_count_ = 0;
};

// For every cell, the row of the next blocked cell at or above it in its
// column (size_y when none), so that "is this column run free?" is one
// lookup. Blocked = not free (occupied or unknown); the outside of the map is
// blocked too. Memory: 4 bytes per cell; built in one pass.
class ColumnBlockIndex {
 public:
  explicit ColumnBlockIndex(const OccupancyGrid& grid);

  int size_x() const { return size_x_; }
  int size_y() const { return size_y_; }
  bool RunIsFree(int ix, int iy_lo, int iy_hi) const {
    if (ix < 0 || ix >= size_x_ || iy_lo < 0 || iy_hi >= size_y_) return false;
    return next_blocked_[static_cast<std::size_t>(ix) * size_y_ + iy_lo] > iy_hi;
  }
  // True when every cell of the stencil placed at (ix, iy) is inside the map
  // and free.
  bool StencilIsFree(const CellStencil& stencil, int ix, int iy) const {
    for (const CellRun& r : stencil.runs())
      if (!RunIsFree(ix + r.dx, iy + r.dy_lo, iy + r.dy_hi)) return false;
    return true;
  }

 private:
  int size_x_ = 0;
  int size_y_ = 0;
  std::vector<std::int32_t> next_blocked_;
};

}  // namespace rc
