#include "workloads/carribot/kernel_footprint_checker.h"

#include "robocore/collision/quadtree_from_grid.h"

namespace rc {
namespace {

// Cells of the padded grid are offset by this ring.
constexpr int kRing = 1;

// The map at 1 cell = 1 unit, blocked = not free, surrounded by a ring of
// blocked cells (the cells outside the map that a footprint centred in the
// map can first touch).
OccupancyGrid PaddedUnitGrid(const OccupancyGrid& grid) {
  OccupancyGrid padded(grid.size_x() + 2 * kRing, grid.size_y() + 2 * kRing, 1.0, CellState::kOccupied);
  for (int ix = 0; ix < grid.size_x(); ++ix)
    for (int iy = 0; iy < grid.size_y(); ++iy)
      if (grid.At(ix, iy) == CellState::kFree) padded.Set(ix + kRing, iy + kRing, CellState::kFree);
  return padded;
}

// Cells' z slab [0, 1]; the footprint sits at its middle with no height.
constexpr double kSlabTop = 1.0;
constexpr double kFootprintZ = 0.5 * kSlabTop;

BoxTree BuildScene(const OccupancyGrid& grid) {
  QuadtreeOptions options;
  options.z_min_m = 0.0;  // "m" here means cells: the grid's resolution is 1
  options.z_max_m = kSlabTop;
  options.unknown_is_occupied = true;
  return BuildQuadtreeFromGrid(PaddedUnitGrid(grid), options);
}

Obbd ToObb(const FootprintPose& pose) {
  Obbd obb;
  obb.centre = {pose.center.x + kRing, pose.center.y + kRing, kFootprintZ};
  const Vec2 a = pose.box.axis;
  obb.axes << a.x, 0.0 - a.y, 0.0,  //
      a.y, a.x, 0.0,                //
      0.0, 0.0, 1.0;
  obb.half = {pose.box.half_length, pose.box.half_width, 0.0};
  return obb;
}

}  // namespace

KernelFootprintChecker::KernelFootprintChecker(const OccupancyGrid& grid)
    : size_x_(grid.size_x()), size_y_(grid.size_y()), tree_(BuildScene(grid)) {
  options_.sact.parallel_epsilon = 0.0;   // why: see the header
  options_.sact.sphere_pretests = false;  // the shipped SACT program has no sphere section
  options_.order = TraversalOrder::kDepthFirst;
}

void KernelFootprintChecker::CheckPoses(const FootprintPose* poses, std::size_t count, std::uint8_t* collides) {
  poses_checked_ += count;
  obbs_.clear();
  slot_.clear();
  for (std::size_t i = 0; i < count; ++i) {
    const Vec2 c = poses[i].center;
    const bool centre_inside = c.x > 0.0 && c.y > 0.0 && c.x < size_x_ && c.y < size_y_;
    collides[i] = 1;
    if (!centre_inside) continue;  // touches a cell outside the map; no kernel query
    obbs_.push_back(ToObb(poses[i]));
    slot_.push_back(i);
  }
  if (obbs_.empty()) return;
  ++batches_;
  kernel_queries_ += obbs_.size();
  if (observer_) {
    CollideBatchInto(tree_, obbs_, options_, &batch_);
    for (std::size_t k = 0; k < slot_.size(); ++k) collides[slot_[k]] = batch_.outcomes[k].collides ? 1 : 0;
    node_visits_ += batch_.visits.size();
    observer_(batch_);
    return;
  }
  CollideBatchRecorded(tree_, obbs_, options_, sample_, &outcomes_, record_observer_ ? &record_ : nullptr);
  for (std::size_t k = 0; k < slot_.size(); ++k) {
    collides[slot_[k]] = outcomes_[k].collides ? 1 : 0;
    node_visits_ += outcomes_[k].nodes_visited;
  }
  if (record_observer_) record_observer_(record_);
}

}  // namespace rc
