#pragma once
// MRPT occupancy maps into an OccupancyGrid.
//
//   .gridmap[.gz]    a serialized COccupancyGridMap2D
//   .simplemap[.gz]  a CSimpleMap (poses + sensory frames); the grid is built
//                    by inserting every frame's observations into a
//                    COccupancyGridMap2D (MRPT's loadFromSimpleMap), with the
//                    insertion options of MRPT's pf-localization demo
//                    (localization_demo.ini): maxDistanceInsertion 15 m,
//                    maxOccupancyUpdateCertainty 0.55, invalid ranges as free.
//
// Values: MRPT stores log-odds; getCell() returns P(free) in [0, 1] (1 =
// free, 0 = occupied, 0.5 = never observed). Verified on MRPT's own data:
// in 2006-MalagaCampus.gridmap 3.25 M of 5.2 M cells are 0.5 (unseen), 1.9 M
// are >= 0.6 (corridors) and 28 k are < 0.4 (walls), so low = occupied, and
// isStaticCell() calls a cell static when getCell() <= threshold. The three
// states follow the rest of rcbench (value_convention.h, ROS thresholds on
// P(occupied) = 1 - P(free)): occupied if P(occupied) >= 0.65, free if
// <= 0.196, unknown otherwise (so 0.5 is unknown).
//
// Frame: MRPT cell (cx, cy) covers [x_min + cx r, x_min + (cx + 1) r) in x
// (likewise y), and becomes our cell (ix, iy) = (cx, cy). Our map frame has
// its origin at the outer corner of cell (0, 0) (occupancy_grid.h), so an
// MRPT world point (X, Y) is the map point (X - x_min, Y - y_min), headings
// unchanged. x_min / y_min are returned so callers can convert poses.
#include <string>

#include "maps/cell_classes.h"
#include "maps/occupancy_grid.h"
#include "maps/value_convention.h"

namespace mrpt::maps {
class COccupancyGridMap2D;  // declared only: this header stays free of MRPT
}

namespace rc {

struct MrptGridMap {
  OccupancyGrid grid;
  double x_min_m = 0.0;              // MRPT world x of our map frame's origin
  double y_min_m = 0.0;              // MRPT world y of our map frame's origin
  ProbabilityThresholds thresholds;  // the ones applied to P(occupied)
  CellClassCounts cell_classes;
};

// Default cell size for grids built from a .simplemap (MRPT's
// localization_demo.ini uses 0.06 m).
inline constexpr double kSimplemapDefaultResolution_m = 0.06;
// Farthest a beam is inserted into a grid built from a .simplemap: 15 m
// (MRPT's localization_demo.ini, maxDistanceInsertion).
inline constexpr float kSimplemapMaxDistanceInsertion_m = 15.0f;

// Throw InputError naming the file for a missing, empty, corrupt or
// truncated archive, an archive of another class, or an empty grid.
// The grid's size is checked against grid_size_limits.h before our copy
// is allocated; for a simplemap, the size MRPT's grid can grow to is
// checked before MRPT inserts the keyframes (simplemap_grid_bound.h).
MrptGridMap LoadMrptGridmap(const std::string& path, const ProbabilityThresholds& thresholds = {});
MrptGridMap LoadMrptSimplemap(const std::string& path, double resolution_m = kSimplemapDefaultResolution_m,
                              const ProbabilityThresholds& thresholds = {});

// Writes the grid as a (gzip-compressed) .gridmap with its origin at
// (x_min_m, y_min_m): free 1.0, occupied 0.0, unknown 0.5 as P(free). For
// tests and for running MRPT's own tools on our maps. Throws
// std::runtime_error when the file cannot be written.
void SaveMrptGridmap(const OccupancyGrid& grid, const std::string& path, double x_min_m = 0.0, double y_min_m = 0.0);

// Sizes `out` to the grid with its origin at (x_min_m, y_min_m) and sets
// every cell: free 1.0, occupied 0.0, unknown 0.5 (as P(free)). Our cell
// (ix, iy) becomes MRPT cell (ix, iy). Throws std::invalid_argument when MRPT
// would size or place the grid differently (origins off its cell lattice).
void ToMrptGrid(const OccupancyGrid& grid, double x_min_m, double y_min_m, mrpt::maps::COccupancyGridMap2D& out);

// One line for the CLI: the value rule and the frame offset.
std::string DescribeMrptGridMap(const MrptGridMap& map);

}  // namespace rc
