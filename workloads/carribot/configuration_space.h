#pragma once
// The configuration space of a rectangular footprint on a grid: one byte per
// (cell, heading) saying whether the footprint centred on that cell at that
// heading is collision-free. Index: grid.Index(ix, iy) * heading_count +
// heading, the state numbering of FootprintStateSpace.
//
// Two builders that must agree exactly:
//  - FromStencils: the footprint stencil of each heading slid over the map
//    (one column lookup per stencil column per state). Cost
//    O(cells * headings * (L + W)): about 0.5 s for the Intel map at scale 4
//    (2 Mi cells) with 8 headings and a 10 x 4 cell robot on a shared 2-core
//    machine; this is what the planner uses.
//  - FromChecker: every (cell, heading) asked of a FootprintChecker, in
//    batches of at most max_batch poses (one heading's cells in storage
//    order, then the next heading). This is how a collision kernel fills the
//    configuration space (one launch per batch: large batches fill a GPU and
//    pay few launches), and how it is held to the exact answer.
// Memory: headings bytes per cell (8 MB for 1 Mi cells at 8 headings).
#include <cstdint>
#include <vector>

#include "maps/occupancy_grid.h"
#include "workloads/carribot/footprint_checker.h"
#include "workloads/carribot/footprint_stencils.h"

namespace rc {

class ConfigurationSpace {
 public:
  static ConfigurationSpace FromStencils(const OccupancyGrid& grid, const FootprintStencils& stencils);
  static constexpr std::size_t kDefaultMaxBatch = 65536;  // poses per launch
  static ConfigurationSpace FromChecker(const OccupancyGrid& grid, const FootprintStencils& stencils,
                                        FootprintChecker& checker, std::size_t max_batch = kDefaultMaxBatch);

  int size_x() const { return size_x_; }
  int size_y() const { return size_y_; }
  int heading_count() const { return heading_count_; }
  bool IsFree(int ix, int iy, int heading) const {
    return free_[(static_cast<std::size_t>(ix) * size_y_ + iy) * heading_count_ + heading] != 0;
  }
  // 1 = collision-free, 0 = in collision; index as above.
  const std::vector<std::uint8_t>& free_states() const { return free_; }
  std::size_t CountFree() const;

 private:
  ConfigurationSpace(int size_x, int size_y, int heading_count);

  int size_x_ = 0;
  int size_y_ = 0;
  int heading_count_ = 0;
  std::vector<std::uint8_t> free_;
};

}  // namespace rc
