#pragma once
// Why a loader gave each cell its state. "Unknown" has two causes that a
// user must be able to tell apart: a value between the free and occupied
// thresholds (the map saw the cell, but not clearly), and no value at all
// (never observed: -1 in a .dat map, 255 in a raw-mode image). On wean.dat
// most mapped cells are of the first kind: the 0.65-0.80 P(free) halo of
// unexplored space around the building (../shared/data/README.md).
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

#include "maps/occupancy_grid.h"

namespace rc {

enum class CellClass : std::uint8_t { kFree, kOccupied, kBetweenThresholds, kUnobserved };

inline CellState StateOf(CellClass c) {
  switch (c) {
    case CellClass::kFree: return CellState::kFree;
    case CellClass::kOccupied: return CellState::kOccupied;
    default: return CellState::kUnknown;
  }
}

struct CellClassCounts {
  std::array<std::size_t, 4> count{};  // indexed by CellClass

  void Add(CellClass c) { ++count[static_cast<std::size_t>(c)]; }
  std::size_t Of(CellClass c) const { return count[static_cast<std::size_t>(c)]; }
  std::size_t Total() const { return count[0] + count[1] + count[2] + count[3]; }
  // "free 61,284 (9.6%), occupied 33,203 (5.2%), between thresholds 105,723
  // (16.5% of all, 60.8% of observed), never observed 439,790 (68.7%)"
  std::string Describe() const;
};

// Counts of a grid whose loader has no thresholds (a MovingAI map): its
// unknown cells count as never observed.
CellClassCounts CountStates(const OccupancyGrid& grid);

}  // namespace rc
