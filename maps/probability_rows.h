#pragma once
// The body shared by the two probability-map formats (CMU wean.dat and
// RoWild DeliBot's variant): size_x lines, one per first index x, of size_y
// values each; a value is a probability in [0, 1] or -1 (never observed).
// Kept in one place so both loaders validate cells identically.
#include "common/text_fields.h"
#include "maps/occupancy_grid.h"
#include "maps/value_convention.h"

namespace rc {

// Reads grid->size_x() rows from reader (positioned just before row 0) and
// classifies every value into grid. Throws InputError naming the line and the
// row or column for a missing row, a wrong value count, a non-number, NaN or
// a value outside [0, 1] other than -1. Adds each cell's class to *counts
// when given.
void ReadProbabilityRows(LineReader& reader, ValueConvention convention, const ProbabilityThresholds& thresholds,
                         OccupancyGrid* grid, CellClassCounts* counts = nullptr);

// Throws InputError at the first non-blank line left in reader.
void RequireNoTrailingData(LineReader& reader);

}  // namespace rc
