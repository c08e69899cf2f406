#pragma once
// A planar scene's tree: a quadtree over a 2D occupancy grid whose leaves
// are the occupied cells, each extruded into a box over a z slab. A planar
// scene never builds a 3D tree (DESIGN.md); the boxes are 3D only so the
// same OBB query and SACT serve both kinds of scene.
//
// The quadtree covers the grid with a square of 2^k cells; a node splits
// its square into four quadrants and keeps the non-empty ones; an internal
// node's bounds are the tight bounds of the occupied cells below it (not
// its square). Leaves are single cells, never merged blocks, so the tree
// answers exactly what testing every occupied cell answers.
// Build: O(cells) time; fewer than 2 nodes per occupied cell (single-child
// internal nodes are dropped, box_tree.h, so every internal node branches).
#include "maps/occupancy_grid.h"
#include "robocore/collision/box_tree.h"

namespace rc {

struct QuadtreeOptions {
  double z_min_m = 0.0;              // m, bottom of every cell's box
  double z_max_m = 2.0;              // m, top: taller than a mobile robot, so its footprint OBB meets a wall
  bool unknown_is_occupied = false;  // CellState::kUnknown as an obstacle
  bool IsValid(std::string* error) const;
};

// The box of cell (ix, iy): [ix r, (ix+1) r] x [iy r, (iy+1) r] x [z_min, z_max]
// in the map frame (maps/occupancy_grid.h).
Aabbd GridCellBox(const OccupancyGrid& grid, int ix, int iy, const QuadtreeOptions& options);

// Throws std::invalid_argument for invalid options.
BoxTree BuildQuadtreeFromGrid(const OccupancyGrid& grid, const QuadtreeOptions& options = {});

}  // namespace rc
