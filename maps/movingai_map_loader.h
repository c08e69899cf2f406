#pragma once
// Loader for MovingAI grid path-finding maps (.map, movingai.com benchmarks):
//   type octile
//   height H
//   width W
//   map
//   H lines of W terrain characters
// Terrain: '.' and 'G' are passable (free). '@' 'O' (out of bounds), 'T'
// (trees), 'S' (swamp) and 'W' (water) are blocked (occupied). MovingAI's
// own notes let some agents cross swamp and water; the benchmark scenarios
// rcbench uses treat them as blocked (../shared/data/README.md), so do we.
//
// Frame: cell (ix, iy) = (column, line of the map body), the x and y of
// MovingAI scenario files, so scenario coordinates index the grid directly.
// Line 0 of the body is y = 0, so the map appears mirrored top to bottom when
// compared with an image of it (whose row 0 is the largest y).
//
// Accepted from other tools: a UTF-8 byte-order mark and CRLF line ends
// (LineReader), and spaces or tabs after a row's last cell. A space inside a
// row is an unknown terrain character.
#include <string>

#include "maps/occupancy_grid.h"

namespace rc {

struct MovingAiMapOptions {
  double resolution_m = 1.0;  // m per cell; the format has no scale
};

// Throws UsageError for a non-positive or non-finite resolution, and
// InputError (file, line, field) for a missing or duplicated header line, a
// type other than octile, an impossible size, a row of the wrong length (not
// counting trailing spaces), an unknown character, too few rows or content
// after the last row.
OccupancyGrid LoadMovingAiMap(const std::string& path, const MovingAiMapOptions& options = {});

}  // namespace rc
