#pragma once
// A large, open warehouse hall: the scene in which laser rays are long
// (issue #20's "paper regime": large open maps, max range 30-80 m), beside
// the office map (office_map_generator.h) in which they are short.
//
// Extent 60 m (x) by 40 m (y), 0.1 m per cell by default (600 x 400 cells).
// Layout (fixed): 0.3 m outer walls; in the western quarter, four rack rows
// 16 m long and 1 m deep, 8 m apart, with 2 m aisles to the west wall; in
// the open hall east of x = 20 m, 0.6 m pillars on a 10 m grid whose rows
// are offset, so no mirror maps the free space onto itself.
// The seed places 12 pallets (1.2 m x 1.0 m) in the open hall, each at least
// 1.5 m from walls, pillars, racks and other pallets, so every free cell
// reaches every other for every seed. No cell on the map border is free;
// no cell is unknown.
#include <cstdint>
#include <string>

#include "maps/occupancy_grid.h"

namespace rc {

constexpr double kHallWidthM = 60.0;
constexpr double kHallHeightM = 40.0;

struct HallMapOptions {
  // m per cell, in [0.05, 0.2]: 0.2 m keeps the 0.6 m pillars three cells
  // wide; below 0.05 m the map exceeds 10^6 cells for no gain.
  double resolution_m = 0.1;
  std::uint64_t seed = 1;  // pallet placement only

  bool IsValid(std::string* error) const;
};

// Throws UsageError if !options.IsValid().
OccupancyGrid GenerateHallMap(const HallMapOptions& options = {});

}  // namespace rc
