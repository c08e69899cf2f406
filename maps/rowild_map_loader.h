#pragma once
// Loader for RoWild DeliBot's map format (cmu-roboarch/rowild, the Monte
// Carlo localization kernel's EnvMap): wean.dat's data with a shorter header.
//   mapsize_x 8000     (extent along x, cm, integer)
//   mapsize_y 8000     (extent along y, cm, integer)
//   resolution 10      (cm per cell, integer)
//   then mapsize_x / resolution lines of mapsize_y / resolution values:
//   line = first index = x, column = y, exactly as wean.dat.
// RoWild reads the three numbers as integers and the rows right after the
// header (a blank line there fails its own assertions), so this loader does
// the same. Where RoWild silently truncates (an extent that is not a whole
// number of cells), this loader reports an error.
// Values are probabilities in [0, 1] or -1 (unknown). RoWild treats them as
// P(occupied); the data are wean.dat's, so the default here is P(free), see
// value_convention.h.
#include <string>

#include "maps/occupancy_grid.h"
#include "maps/value_convention.h"

namespace rc {

struct RowildMapOptions {
  ValueConvention convention = ValueConvention::kProbabilityFree;
  ProbabilityThresholds thresholds;
};

// Throws InputError (file, line, field) on any malformed or truncated input.
// Adds each cell's class to *counts when given.
OccupancyGrid LoadRowildMap(const std::string& path, const RowildMapOptions& options = {},
                            CellClassCounts* counts = nullptr);

}  // namespace rc
