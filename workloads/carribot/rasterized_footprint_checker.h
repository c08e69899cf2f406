#pragma once
// The exact reference FootprintChecker: a separating-axis test of the
// rectangle against every blocked cell square in its bounding box (cells
// outside the map count as blocked). Cost per pose: one SAT (4 axes) per
// candidate cell, about (length + 2) * (width + 2) cells at worst for a
// diagonal heading; no precomputation beyond a copy of the free cells.
#include <vector>

#include "maps/occupancy_grid.h"
#include "workloads/carribot/footprint_checker.h"

namespace rc {

class RasterizedFootprintChecker final : public FootprintChecker {
 public:
  explicit RasterizedFootprintChecker(const OccupancyGrid& grid);

  const char* name() const override { return "rasterized"; }
  void CheckPoses(const FootprintPose* poses, std::size_t count, std::uint8_t* collides) override;
  std::uint64_t poses_checked() const override { return poses_checked_; }
  // Cell squares tested with the SAT since construction (the work measure).
  std::uint64_t cell_tests() const { return cell_tests_; }

  bool Collides(const FootprintPose& pose);

 private:
  bool IsBlocked(int ix, int iy) const {
    return ix < 0 || iy < 0 || ix >= size_x_ || iy >= size_y_ ||
           free_[static_cast<std::size_t>(ix) * size_y_ + iy] == 0;
  }

  int size_x_ = 0;
  int size_y_ = 0;
  std::vector<std::uint8_t> free_;
  std::uint64_t poses_checked_ = 0;
  std::uint64_t cell_tests_ = 0;
};

}  // namespace rc
