#pragma once
// What every successful parse must satisfy, whatever the bytes: a reader
// never returns a value it would have to reject ("nothing silently fixed").
#include <cmath>

#include "fuzz/fuzz_input_file.h"
#include "maps/occupancy_grid.h"
#include "traces/sensor_trace.h"

namespace rc::fuzz {

inline void RequireValidGrid(const OccupancyGrid& grid) {
  Require(grid.size_x() > 0 && grid.size_y() > 0, "the grid is empty");
  Require(grid.cell_count() == static_cast<std::size_t>(grid.size_x()) * static_cast<std::size_t>(grid.size_y()),
          "the cell count differs from size_x * size_y");
  Require(std::isfinite(grid.resolution_m()) && grid.resolution_m() > 0.0, "the resolution is not positive");
  for (CellState s : grid.cells())
    Require(s == CellState::kFree || s == CellState::kOccupied || s == CellState::kUnknown,
            "a cell holds no valid state");
}

inline bool Finite(const Pose2& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.theta); }

inline void RequireValidTrace(const SensorTrace& trace) {
  const LaserGeometry& g = trace.geometry;
  Require(!trace.scans.empty(), "the trace has no scan");
  Require(g.beam_count > 0, "the beam count is not positive");
  Require(std::isfinite(g.angle_min_rad) && std::isfinite(g.angle_increment_rad) && std::isfinite(g.max_range_m) &&
              std::isfinite(g.offset_forward_m),
          "the laser geometry is not finite");
  for (const LaserScan& scan : trace.scans) {
    Require(scan.ranges_m.size() == static_cast<std::size_t>(g.beam_count), "a scan's beam count differs");
    Require(Finite(scan.odometry) && std::isfinite(scan.time_s), "a scan's pose or time is not finite");
    for (float r : scan.ranges_m) Require(std::isfinite(r) && r >= 0.0f, "a range is negative or not finite");
  }
}

}  // namespace rc::fuzz
