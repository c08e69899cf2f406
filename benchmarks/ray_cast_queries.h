#pragma once
// The ray-cast benchmark's queries (issue 24's RangeLibc setting), shared
// by ray_cast_benchmark.cc and the GPU check's exporter
// (gpu/ray_cast_export.cc), so that both cast the very same rays: starts
// uniform in free cells, headings uniform, seed 1, in random order; and the
// grid order (sorted by start cell column, then y), as a permutation.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "common/random_stream.h"
#include "maps/occupancy_grid.h"
#include "robocore/ray_batch.h"

namespace rc {

struct RayCastQueries {
  std::vector<RayQuery> random_order;
  std::vector<std::uint32_t> grid_order;  // query index at each grid-order position
};

inline RayCastQueries MakeRayCastQueries(const OccupancyGrid& grid, std::size_t count) {
  RayCastQueries q;
  const std::vector<std::uint32_t> free_cells = grid.FreeCellIndices();
  RandomStream s(1, StreamPurpose::kTest, 0, 0);
  const double r = grid.resolution_m();
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint32_t c = free_cells[s.Below(free_cells.size())];
    const int ix = static_cast<int>(c / grid.size_y()), iy = static_cast<int>(c % grid.size_y());
    const double x = (ix + s.Uniform()) * r, y = (iy + s.Uniform()) * r;
    q.random_order.push_back({x, y, s.Uniform(-3.14159265, 3.14159265)});
  }
  q.grid_order.resize(count);
  for (std::size_t i = 0; i < count; ++i) q.grid_order[i] = static_cast<std::uint32_t>(i);
  std::stable_sort(q.grid_order.begin(), q.grid_order.end(), [&](std::uint32_t a, std::uint32_t b) {
    const RayQuery &qa = q.random_order[a], &qb = q.random_order[b];
    const int ax = static_cast<int>(qa.origin_x_m / r), bx = static_cast<int>(qb.origin_x_m / r);
    return ax != bx ? ax < bx : qa.origin_y_m < qb.origin_y_m;
  });
  return q;
}

}  // namespace rc
