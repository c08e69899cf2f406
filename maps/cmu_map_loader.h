#pragma once
// Loader for the CMU robot-localization map format (wean.dat):
//   robot_specifications->global_mapsize_x  8000     (cm)
//   robot_specifications->global_mapsize_y  8000     (cm)
//   robot_specifications->resolution        10       (cm per cell)
//   robot_specifications->autoshifted_x/y   0
//   global_map[0]: 800 800                           (size_x size_y)
//   800 lines of 800 values: line = first index = x, column = y.
// Values are probabilities in [0, 1] or -1 (unknown). Default convention:
// P(free), see value_convention.h for the evidence.
#include <string>

#include "maps/occupancy_grid.h"
#include "maps/value_convention.h"

namespace rc {

struct CmuMapOptions {
  ValueConvention convention = ValueConvention::kProbabilityFree;
  ProbabilityThresholds thresholds;
};

// Throws InputError (file, line, field) on any malformed or truncated input,
// and for a declared size beyond the limits of grid_size_limits.h before
// allocating it. Adds each cell's class to *counts when given.
OccupancyGrid LoadCmuMap(const std::string& path, const CmuMapOptions& options = {}, CellClassCounts* counts = nullptr);

}  // namespace rc
