#include "maps/mrpt/simplemap_grid_bound.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <mrpt/maps/COccupancyGridMap2D.h>
#include <mrpt/maps/CSimpleMap.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservationRange.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/poses/CPose3D.h>

#include "common/input_error.h"
#include "common/memory_cap.h"
#include "maps/grid_size_limits.h"

namespace rc {
namespace {

std::string Keyframe(std::size_t k) { return "keyframe " + std::to_string(k); }

std::string Metres(double v) {
  std::ostringstream text;
  text.precision(4);
  text << v;
  return text.str();
}

// The rectangle every beam end lies in, and the keyframe that reaches
// farthest from the cleared grid (named when the bound is refused).
class Extent {
 public:
  Extent()
      : x_min_(-kMrptClearedGridHalfSide_m),
        x_max_(kMrptClearedGridHalfSide_m),
        y_min_(-kMrptClearedGridHalfSide_m),
        y_max_(kMrptClearedGridHalfSide_m) {}

  // A sensor at (x, y) whose beam ends lie within `reach_m` of it.
  void Add(double x, double y, double reach_m, std::size_t keyframe) {
    x_min_ = std::min(x_min_, x - reach_m);
    x_max_ = std::max(x_max_, x + reach_m);
    y_min_ = std::min(y_min_, y - reach_m);
    y_max_ = std::max(y_max_, y + reach_m);
    const double distance = std::max(std::abs(x), std::abs(y)) + reach_m;
    if (distance > farthest_m_) {
      farthest_m_ = distance;
      farthest_keyframe_ = keyframe;
    }
  }

  SimplemapGridBound Bound(double resolution_m) const {
    const double margin = kMrptGrowthMargin_m + kMrptGrowthMarginCells * resolution_m;
    SimplemapGridBound b;
    b.x_min_m = x_min_ - margin;
    b.x_max_m = x_max_ + margin;
    b.y_min_m = y_min_ - margin;
    b.y_max_m = y_max_ + margin;
    return b;
  }
  std::size_t farthest_keyframe() const { return farthest_keyframe_; }

 private:
  double x_min_, x_max_, y_min_, y_max_;
  double farthest_m_ = 0.0;
  std::size_t farthest_keyframe_ = 0;
};

void RequireFinite(const mrpt::poses::CPose3D& pose, const std::string& path, const std::string& field,
                   const std::string& what) {
  if (!std::isfinite(pose.x()) || !std::isfinite(pose.y()) || !std::isfinite(pose.z()) || !std::isfinite(pose.yaw()) ||
      !std::isfinite(pose.pitch()) || !std::isfinite(pose.roll()))
    throw InputError(path, 0, field, what + " is not finite");
}

void RequireDistance(float range_m, const std::string& path, const std::string& field) {
  if (!std::isfinite(range_m) || range_m < 0.0f)
    throw InputError(path, 0, field, "range " + Metres(range_m) + " m is not a distance");
}

// Adds one observation's beam ends; other observation types leave a 2D
// grid unchanged (MRPT ignores them).
void AddObservation(const mrpt::obs::CObservation& observation, const mrpt::poses::CPose3D& robot,
                    const mrpt::maps::COccupancyGridMap2D& grid, const std::string& path, std::size_t keyframe,
                    const std::string& field, Extent& extent) {
  const double max_insertion_m = grid.insertionOptions.maxDistanceInsertion;
  if (const auto* scan = dynamic_cast<const mrpt::obs::CObservation2DRangeScan*>(&observation)) {
    if (!scan->isPlanarScan(grid.insertionOptions.horizontalTolerance)) return;  // MRPT skips it
    RequireFinite(scan->sensorPose, path, field + " sensorPose", "the laser's pose on the robot");
    if (!std::isfinite(scan->aperture)) throw InputError(path, 0, field + " aperture", "not finite");
    const std::size_t n = scan->getScanSize();
    if (n > static_cast<std::size_t>(kMaxSimplemapScanBeams))
      throw InputError(path, 0, field + " scan size",
                       std::to_string(n) + " beams; at most " + std::to_string(kMaxSimplemapScanBeams) +
                           " are read (MRPT keeps two floats per beam on the stack)");
    for (std::size_t i = 0; i < n; ++i)
      if (scan->getScanRangeValidity(i))
        RequireDistance(scan->getScanRange(i), path, field + " range " + std::to_string(i));
    const mrpt::poses::CPose2D sensor(robot + scan->sensorPose);
    extent.Add(sensor.x(), sensor.y(), max_insertion_m, keyframe);
  } else if (const auto* ranges = dynamic_cast<const mrpt::obs::CObservationRange*>(&observation)) {
    mrpt::poses::CPose3D mount;
    ranges->getSensorPose(mount);
    RequireFinite(mount, path, field + " sensorPose", "the range sensor's pose on the robot");
    if (!std::isfinite(ranges->sensorConeApperture))
      throw InputError(path, 0, field + " sensorConeApperture", "not finite");
    for (std::size_t i = 0; i < ranges->sensedData.size(); ++i)
      RequireDistance(ranges->sensedData[i].sensedDistance, path, field + " range " + std::to_string(i));
    const mrpt::poses::CPose2D sensor(robot + mount);
    extent.Add(sensor.x(), sensor.y(), max_insertion_m, keyframe);
  }
}

}  // namespace

SimplemapGridBound CheckSimplemapGridBound(const mrpt::maps::CSimpleMap& simple,
                                           const mrpt::maps::COccupancyGridMap2D& grid, const std::string& path) {
  Extent extent;
  std::size_t keyframe = 0;
  for (const auto& pair : simple) {
    // A null pose or frame: MRPT raises its own exception at that keyframe.
    if (pair.pose && pair.sf) {
      const mrpt::poses::CPose3D robot = pair.pose->getMeanVal();
      RequireFinite(robot, path, Keyframe(keyframe) + " pose", "the keyframe's mean pose");
      std::size_t index = 0;
      for (const auto& observation : *pair.sf) {
        if (observation)
          AddObservation(*observation, robot, grid, path, keyframe,
                         Keyframe(keyframe) + " observation " + std::to_string(index), extent);
        ++index;
      }
    }
    ++keyframe;
  }
  const double resolution_m = grid.getResolution();
  SimplemapGridBound bound = extent.Bound(resolution_m);
  const double cells_x = std::ceil((bound.x_max_m - bound.x_min_m) / resolution_m);
  const double cells_y = std::ceil((bound.y_max_m - bound.y_min_m) / resolution_m);
  const std::string field = Keyframe(extent.farthest_keyframe()) + " pose";
  const std::string span = "the grid MRPT builds from the simplemap's scans reaches x in [" + Metres(bound.x_min_m) +
                           ", " + Metres(bound.x_max_m) + "] m, y in [" + Metres(bound.y_min_m) + ", " +
                           Metres(bound.y_max_m) + "] m (" + Metres(cells_x) + " x " + Metres(cells_y) + " cells at " +
                           Metres(resolution_m) + " m; this keyframe's scans reach farthest)";
  if (!(cells_x <= kMaxMapCellsPerSide) || !(cells_y <= kMaxMapCellsPerSide))
    throw InputError(path, 0, field,
                     span + ": each side must be at most " + std::to_string(kMaxMapCellsPerSide) + " cells");
  bound.size_x = static_cast<long long>(cells_x);
  bound.size_y = static_cast<long long>(cells_y);
  CheckMapSize(path, 0, field, static_cast<long>(bound.size_x), static_cast<long>(bound.size_y));
  const std::uint64_t cells = static_cast<std::uint64_t>(bound.size_x) * static_cast<std::uint64_t>(bound.size_y);
  const std::uint64_t need = BytesFor(cells, 2 * sizeof(mrpt::maps::COccupancyGridMap2D::cellType) + sizeof(CellState));
  if (need > MemoryCapBytes()) throw InputError(path, 0, field, span + ": " + DescribeOverCap(need));
  return bound;
}

}  // namespace rc
