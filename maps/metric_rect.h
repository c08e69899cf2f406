// Axis-aligned rectangles in the map frame, and painting them into a grid:
// the shared vocabulary of the map generators (office, hall).
#pragma once

#include "maps/occupancy_grid.h"

namespace rc {

// An axis-aligned rectangle [x0, x1) x [y0, y1) in the map frame (m).
struct MetricRect {
  double x0_m, y0_m, x1_m, y1_m;
};

// Cells [x0, x1) x [y0, y1) whose centres lie inside a rectangle, clamped
// to the grid.
struct CellRange {
  int x0, y0, x1, y1;
};
CellRange CellsOf(const MetricRect& r, const OccupancyGrid& grid);

// Sets every cell whose centre lies inside `r` to `s`.
void FillRect(const MetricRect& r, CellState s, OccupancyGrid* grid);

// True when every such cell is free.
bool AllFree(const MetricRect& r, const OccupancyGrid& grid);

MetricRect Inflate(const MetricRect& r, double dx, double dy);
bool Overlaps(const MetricRect& a, const MetricRect& b);

// Marks the grid's outermost ring of cells occupied: when the resolution
// does not divide the extent, the last cell's centre can fall outside an
// outer wall drawn in metres.
void CloseBorder(OccupancyGrid* grid);

}  // namespace rc
