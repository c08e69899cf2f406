#pragma once
// Map scaling as RoWild's CarriBot does it (--scale-map): every cell becomes
// factor x factor cells of the same state, so the map keeps its metric extent
// and the resolution is divided by the factor. Planning on it costs about
// factor^2 more states; that is the point of the Intel scale 1 / 2 / 4 runs.
#include "maps/occupancy_grid.h"

namespace rc {

// Throws std::invalid_argument for a factor below 1 or a result too large
// for OccupancyGrid.
OccupancyGrid UpscaleGrid(const OccupancyGrid& grid, int factor);

}  // namespace rc
