#include "maps/metric_rect.h"

#include <algorithm>
#include <cmath>

namespace rc {

CellRange CellsOf(const MetricRect& r, const OccupancyGrid& grid) {
  const double res = grid.resolution_m();
  auto first = [res](double v) { return static_cast<int>(std::ceil(v / res - 0.5)); };
  return {std::max(0, first(r.x0_m)), std::max(0, first(r.y0_m)), std::min(grid.size_x(), first(r.x1_m)),
          std::min(grid.size_y(), first(r.y1_m))};
}

void FillRect(const MetricRect& r, CellState s, OccupancyGrid* grid) {
  const CellRange c = CellsOf(r, *grid);
  for (int ix = c.x0; ix < c.x1; ++ix)
    for (int iy = c.y0; iy < c.y1; ++iy) grid->Set(ix, iy, s);
}

bool AllFree(const MetricRect& r, const OccupancyGrid& grid) {
  const CellRange c = CellsOf(r, grid);
  for (int ix = c.x0; ix < c.x1; ++ix)
    for (int iy = c.y0; iy < c.y1; ++iy)
      if (grid.At(ix, iy) != CellState::kFree) return false;
  return true;
}

MetricRect Inflate(const MetricRect& r, double dx, double dy) {
  return {r.x0_m - dx, r.y0_m - dy, r.x1_m + dx, r.y1_m + dy};
}

bool Overlaps(const MetricRect& a, const MetricRect& b) {
  return a.x0_m < b.x1_m && b.x0_m < a.x1_m && a.y0_m < b.y1_m && b.y0_m < a.y1_m;
}

void CloseBorder(OccupancyGrid* grid) {
  const int sx = grid->size_x(), sy = grid->size_y();
  for (int ix = 0; ix < sx; ++ix) {
    grid->Set(ix, 0, CellState::kOccupied);
    grid->Set(ix, sy - 1, CellState::kOccupied);
  }
  for (int iy = 0; iy < sy; ++iy) {
    grid->Set(0, iy, CellState::kOccupied);
    grid->Set(sx - 1, iy, CellState::kOccupied);
  }
}

}  // namespace rc
