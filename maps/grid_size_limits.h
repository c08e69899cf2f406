#pragma once
// Upper bounds on the size a map file may declare. A corrupt or hostile
// header must produce an InputError, not a multi-gigabyte allocation or the
// OccupancyGrid constructor's std::invalid_argument.
#include <string>

#include <cstdint>

#include "common/input_error.h"
#include "common/memory_cap.h"
#include "maps/occupancy_grid.h"

namespace rc {

// 10 km at 10 cm per cell; far beyond any real floor plan.
constexpr long kMaxMapCellsPerSide = 100000;
// 256 Mi cells = 256 MiB of CellState; the largest real map used (wean.dat)
// has 0.64 Mi.
constexpr long long kMaxMapCells = 1LL << 28;

// Throws InputError(file, line, field, ...) unless 1 <= size_x, size_y <=
// kMaxMapCellsPerSide, size_x * size_y <= kMaxMapCells, and the grid's cells
// fit the memory cap (common/memory_cap.h). Loaders call it before they
// allocate the grid.
inline void CheckMapSize(const std::string& file, long line, const std::string& field, long size_x, long size_y) {
  if (size_x < 1 || size_y < 1 || size_x > kMaxMapCellsPerSide || size_y > kMaxMapCellsPerSide)
    throw InputError(file, line, field,
                     "map size " + std::to_string(size_x) + " x " + std::to_string(size_y) +
                         " cells is impossible (each side must be in [1, " + std::to_string(kMaxMapCellsPerSide) +
                         "])");
  if (static_cast<long long>(size_x) * size_y > kMaxMapCells)
    throw InputError(file, line, field,
                     "map size " + std::to_string(size_x) + " x " + std::to_string(size_y) +
                         " cells exceeds the limit of " + std::to_string(kMaxMapCells) + " cells");
  const std::uint64_t need =
      BytesFor(static_cast<std::uint64_t>(size_x) * static_cast<std::uint64_t>(size_y), sizeof(CellState));
  if (need > MemoryCapBytes())
    throw InputError(file, line, field,
                     "map size " + std::to_string(size_x) + " x " + std::to_string(size_y) + " cells " +
                         DescribeOverCap(need));
}

}  // namespace rc
