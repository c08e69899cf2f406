#pragma once
// A small, deterministic, office-like map for the default demo and the tests.
//
// Extent 20 m (x) by 15 m (y), 0.05 m per cell by default (400 x 300 cells):
// fine enough that 0.2 m walls are 4 cells thick and a laser ray's cell
// walk is long enough to matter, small enough to build in milliseconds.
// Layout (fixed): outer walls; a 2 m corridor along y = 6.2..8.2 m from the
// west wall to an open lobby at the east end (x > 15.2 m); three rooms south
// of the corridor and two north of it, one with a storage room inside; doors
// 1.1 to 1.3 m wide at unequal positions; three lobby pillars, a reception
// counter, a conference table and a pillar in the north office. Room sizes,
// door positions and pillars are deliberately unequal, so no rotation or
// mirror maps the free space onto itself and global localization has a
// unique answer.
// The seed moves only the furniture: 2 to 4 desks, cabinets, tables or
// shelves per room, each either flush with a wall or at least 0.7 m from
// walls and other furniture, never within 1.2 m of a doorway. A piece that
// would cut the free space in two is dropped, so every free cell reaches
// every other (4-connectivity) for every seed; no cell on the map border is
// free; no cell is unknown.
#include <cstdint>
#include <string>
#include <vector>

#include "maps/metric_rect.h"
#include "maps/occupancy_grid.h"

namespace rc {

constexpr double kOfficeWidthM = 20.0;
constexpr double kOfficeHeightM = 15.0;

struct OfficeMapOptions {
  // m per cell, in [0.02, 0.1]; coarser cells would shrink 1.1 m doors below
  // 1 m and 0.2 m walls below two cells.
  double resolution_m = 0.05;
  std::uint64_t seed = 1;  // furniture placement only

  bool IsValid(std::string* error) const;
};

// The door openings (including the corridor's 2 m mouth into the lobby),
// the same for every seed and resolution.
const std::vector<MetricRect>& OfficeDoorOpenings();

// Throws UsageError if !options.IsValid().
OccupancyGrid GenerateOfficeMap(const OfficeMapOptions& options = {});

}  // namespace rc
