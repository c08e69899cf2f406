#include "robocore/collision/quadtree_from_grid.h"

#include <cmath>
#include <stdexcept>

namespace rc {
namespace {

struct QuadtreeBuilder {
  const OccupancyGrid& grid;
  const QuadtreeOptions& options;
  std::vector<Aabbd> boxes;
  std::vector<BuildNode> pool;

  bool IsObstacle(int ix, int iy) const {
    if (!grid.Contains(ix, iy)) return false;
    const CellState s = grid.At(ix, iy);
    return s == CellState::kOccupied || (options.unknown_is_occupied && s == CellState::kUnknown);
  }

  // The node for the square [x0, x0 + size) x [y0, y0 + size), or kNoBox
  // when it holds no obstacle.
  std::uint32_t Build(int x0, int y0, int size) {
    if (x0 >= grid.size_x() || y0 >= grid.size_y()) return kNoBox;
    if (size == 1) {
      if (!IsObstacle(x0, y0)) return kNoBox;
      boxes.push_back(GridCellBox(grid, x0, y0, options));
      pool.emplace_back();
      pool.back().box = static_cast<std::uint32_t>(boxes.size() - 1);
      return static_cast<std::uint32_t>(pool.size() - 1);
    }
    const int h = size / 2;
    BuildNode node;
    const int offsets[4][2] = {{0, 0}, {h, 0}, {0, h}, {h, h}};
    for (const auto& offset : offsets) {
      const std::uint32_t child = Build(x0 + offset[0], y0 + offset[1], h);
      if (child != kNoBox) node.children.push_back(child);
    }
    if (node.children.empty()) return kNoBox;
    pool.push_back(std::move(node));
    return static_cast<std::uint32_t>(pool.size() - 1);
  }
};

}  // namespace

bool QuadtreeOptions::IsValid(std::string* error) const {
  if (!std::isfinite(z_min_m) || !std::isfinite(z_max_m) || z_max_m < z_min_m) {
    if (error) *error = "the z slab needs finite z_min_m <= z_max_m";
    return false;
  }
  return true;
}

Aabbd GridCellBox(const OccupancyGrid& grid, int ix, int iy, const QuadtreeOptions& options) {
  const double r = grid.resolution_m();
  Aabbd box;
  box.centre = {(ix + 0.5) * r, (iy + 0.5) * r, 0.5 * (options.z_min_m + options.z_max_m)};
  box.half = {0.5 * r, 0.5 * r, 0.5 * (options.z_max_m - options.z_min_m)};
  return box;
}

BoxTree BuildQuadtreeFromGrid(const OccupancyGrid& grid, const QuadtreeOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument("quadtree: " + error);
  int side = 1;
  while (side < grid.size_x() || side < grid.size_y()) side *= 2;
  QuadtreeBuilder b{grid, options, {}, {}};
  const std::uint32_t root = grid.cell_count() == 0 ? kNoBox : b.Build(0, 0, side);
  if (root == kNoBox) return LayOutBreadthFirst(BoxTreeKind::kQuadtree, 4, {}, {}, 0);
  return LayOutBreadthFirst(BoxTreeKind::kQuadtree, 4, std::move(b.boxes), b.pool, root);
}

}  // namespace rc
