#pragma once
// How a loader turns a stored cell value into a CellState.
//
// Probability maps (wean.dat and its RoWild variant) store a number in [0, 1]
// per cell, or -1 for "never observed". What the number means differs by
// source, so it is an explicit option:
//   - kProbabilityFree: the value is P(free). This is what wean.dat holds:
//     rendered, its corridors are near 1 and its walls near 0, and the robot's
//     5 m readings fit only under this reading (../shared/data/README.md).
//     Its own format note (instruct.txt) says the opposite; the data wins.
//   - kProbabilityOccupied: the value is P(occupied), as the note claims and
//     as RoWild's DeliBot reads it (which inverts the map).
// Thresholds follow ROS map_server's trinary mode, applied to P(occupied):
// occupied when p >= occupied_thresh, free when p <= free_thresh, unknown
// otherwise.
#include <string>

#include "maps/cell_classes.h"
#include "maps/occupancy_grid.h"

namespace rc {

enum class ValueConvention { kProbabilityFree, kProbabilityOccupied };

struct ProbabilityThresholds {
  double occupied_thresh = 0.65;  // P(occupied) at or above: occupied (ROS default)
  double free_thresh = 0.196;     // P(occupied) at or below: free (ROS default)
  // Stored values below this mean "unknown" (wean.dat uses -1).
  double unknown_below = 0.0;
};

// Parses "free" / "occupied" (as given on the command line).
ValueConvention ParseValueConvention(const std::string& name);
std::string ToString(ValueConvention c);

// value is the stored number; returns why the cell gets its state under
// the convention (cell_classes.h).
inline CellClass ClassifyProbabilityValue(double value, ValueConvention convention, const ProbabilityThresholds& t) {
  if (value < t.unknown_below) return CellClass::kUnobserved;
  const double p_occupied = convention == ValueConvention::kProbabilityFree ? 1.0 - value : value;
  if (p_occupied >= t.occupied_thresh) return CellClass::kOccupied;
  if (p_occupied <= t.free_thresh) return CellClass::kFree;
  return CellClass::kBetweenThresholds;
}

inline CellState ClassifyProbability(double value, ValueConvention convention, const ProbabilityThresholds& t) {
  return StateOf(ClassifyProbabilityValue(value, convention, t));
}

// Throws UsageError unless 0 <= free_thresh < occupied_thresh <= 1 (the
// thresholds apply to P(occupied), as ROS map_server's do).
void CheckProbabilityThresholds(const ProbabilityThresholds& t);

}  // namespace rc
