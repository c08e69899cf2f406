#pragma once
// Connectivity of a grid's free space, for generators that must not leave
// unreachable pockets and for tests of planners' inputs.
// Cost: one pass over the cells plus a 4-byte label per cell.
#include <cstddef>

#include "maps/occupancy_grid.h"

namespace rc {

// Number of 4-connected components of free cells (0 when no cell is free).
// Unknown and occupied cells both separate components.
std::size_t CountFreeComponents(const OccupancyGrid& grid);

}  // namespace rc
