#pragma once
// An upper bound on the occupancy grid MRPT builds from a simplemap
// (COccupancyGridMap2D::loadFromSimpleMap), computed from the keyframe
// poses, the sensor poses and the ranges before MRPT inserts anything.
//
// Why it is needed: MRPT grows the grid as it inserts each observation, in
// COccupancyGridMap2D::resizeGrid, which is declared noexcept. An
// allocation refused there (std::bad_alloc, or the AllocationBudget's
// refusal) cannot leave MRPT and terminates the process (a tests/fuzz
// finding: two keyframes whose scans lie 10^30 m apart). So the size the
// grid can reach is bounded and checked first, and MRPT then inserts under
// no allocation budget.
#include <string>

namespace mrpt::maps {
class CSimpleMap;  // declared only: this header stays free of MRPT
class COccupancyGridMap2D;
}  // namespace mrpt::maps

namespace rc {

// MRPT's growth rules (MRPT 2.5, COccupancyGridMap2D_insert.cpp and
// COccupancyGridMap2D_common.cpp), which the bound follows:
// - loadFromSimpleMap first clears the grid to [-10, 10] m on both axes
//   (kMrptClearedGridHalfSide_m).
// - A 2D scan (CObservation2DRangeScan, planar within the grid's
//   horizontalTolerance) or a CObservationRange places every beam's end at
//   most min(maxDistanceInsertion, range) from the sensor, a non-negative
//   range assumed (negative or NaN ranges are refused below).
// - When the ends come within 15 cells of the high edge, that edge moves to
//   the farthest end + 30 cells; of the low edge, to the farthest end - 2 m;
//   resizeGrid then adds 4 m, rounds outwards to whole metres and to the
//   cell lattice. Hence each edge lies within kMrptGrowthMargin_m +
//   kMrptGrowthMarginCells cells of the farthest beam end.
// kMrptClearedGridHalfSide_m: 10 m, fixed by MRPT (internal_clear).
inline constexpr double kMrptClearedGridHalfSide_m = 10.0;
// kMrptGrowthMargin_m: 7 m, range [7, 8]: 2 m (insertion) + 4 m (resizeGrid)
// + under 1 m (rounding to whole metres).
inline constexpr double kMrptGrowthMargin_m = 7.0;
// kMrptGrowthMarginCells: 32 cells, range [31, 40]: 2 x 15 cells (insertion),
// half a cell (lattice rounding), one cell for the float arithmetic MRPT
// places beam ends with.
inline constexpr double kMrptGrowthMarginCells = 32.0;
// kMaxSimplemapScanBeams: 100,000 beams per scan, range [10^4, 10^6]. MRPT
// keeps two floats per beam on the stack (alloca) while it inserts a scan:
// 0.8 MB at this limit, a tenth of Linux's default 8 MiB stack. Real 2D
// lasers have 181 (SICK LMS 200) to 1,081 (Hokuyo UTM-30LX) beams.
inline constexpr long kMaxSimplemapScanBeams = 100000;

// The MRPT world rectangle the grid stays inside, and its size in cells
// (rounded up).
struct SimplemapGridBound {
  double x_min_m = 0.0, x_max_m = 0.0, y_min_m = 0.0, y_max_m = 0.0;
  long long size_x = 0, size_y = 0;
};

// The bound for inserting `simple` into `grid` with the grid's resolution
// and insertion options. Throws InputError naming `path` and the keyframe
// (0-based) when a keyframe pose, a sensor pose, a scan aperture or a range
// is not finite or a range is negative (MRPT would place beam ends at
// infinity), when a scan has more than kMaxSimplemapScanBeams beams, and
// when the bound is an impossible map (CheckMapSize) or MRPT's grid and
// ours would not fit the memory cap together (MRPT holds the old and the
// new cells while it resizes: two bytes a cell, plus our CellState).
SimplemapGridBound CheckSimplemapGridBound(const mrpt::maps::CSimpleMap& simple,
                                           const mrpt::maps::COccupancyGridMap2D& grid, const std::string& path);

}  // namespace rc
