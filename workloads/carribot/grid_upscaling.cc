#include "workloads/carribot/grid_upscaling.h"

#include <stdexcept>

#include "maps/grid_size_limits.h"

namespace rc {

OccupancyGrid UpscaleGrid(const OccupancyGrid& grid, int factor) {
  if (factor < 1) throw std::invalid_argument("map scale factor must be >= 1");
  const long long sx = static_cast<long long>(grid.size_x()) * factor;
  const long long sy = static_cast<long long>(grid.size_y()) * factor;
  if (sx > kMaxMapCellsPerSide || sy > kMaxMapCellsPerSide || sx * sy > kMaxMapCells)
    throw std::invalid_argument("map scale factor " + std::to_string(factor) + " makes the map too large");
  OccupancyGrid scaled(static_cast<int>(sx), static_cast<int>(sy), grid.resolution_m() / factor);
  for (int ix = 0; ix < scaled.size_x(); ++ix)
    for (int iy = 0; iy < scaled.size_y(); ++iy) scaled.Set(ix, iy, grid.At(ix / factor, iy / factor));
  return scaled;
}

}  // namespace rc
