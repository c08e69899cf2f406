#include "workloads/carribot/footprint_state_space.h"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

#include "workloads/carribot/octile_steps.h"

namespace rc {

FootprintStateSpace::FootprintStateSpace(const OccupancyGrid& grid, const FootprintStencils& stencils,
                                         FootprintCheckMode mode, FootprintChecker* checker)
    : size_x_(grid.size_x()),
      size_y_(grid.size_y()),
      heading_count_(stencils.heading_count()),
      stencils_(stencils),
      mode_(mode),
      checker_(checker),
      turn_cost_(stencils.half_diagonal_cells() * 2.0 * 3.14159265358979323846 / stencils.heading_count()),
      blocks_(grid) {
  if (static_cast<double>(grid.cell_count()) * heading_count_ >= 4.0e9)
    throw std::invalid_argument("FootprintStateSpace: map x headings exceeds 32-bit state ids");
  if (mode == FootprintCheckMode::kPerExpansion && checker == nullptr)
    throw std::invalid_argument("FootprintStateSpace: per-expansion checking needs a FootprintChecker");
  if (mode == FootprintCheckMode::kPrecomputed)
    cspace_ = std::make_unique<ConfigurationSpace>(checker != nullptr
                                                       ? ConfigurationSpace::FromChecker(grid, stencils, *checker)
                                                       : ConfigurationSpace::FromStencils(grid, stencils));
}

bool FootprintStateSpace::IsPoseFree(int ix, int iy, int heading) {
  ++collision_queries_;
  if (cspace_) return cspace_->IsFree(ix, iy, heading);
  const FootprintPose pose = stencils_.PoseAt(ix, iy, heading);
  std::uint8_t collides = 1;
  checker_->CheckPoses(&pose, 1, &collides);
  return collides == 0;
}

void FootprintStateSpace::SetGoal(int gx, int gy, int goal_heading) {
  goal_x_ = gx;
  goal_y_ = gy;
  goal_heading_ = goal_heading;
  collision_queries_ = 0;
}

double FootprintStateSpace::Heuristic(StateId s) const {
  double h = OctileDistance(CellX(s) - goal_x_, CellY(s) - goal_y_);
  if (goal_heading_ != kAnyHeading) {
    const int diff = std::abs(Heading(s) - goal_heading_);
    h += std::min(diff, heading_count_ - diff) * turn_cost_;
  }
  return h;
}

double FootprintStateSpace::MotionCost(std::uint8_t motion) const {
  return motion < 8 ? OctileStepCost(motion) : turn_cost_;
}

bool FootprintStateSpace::Target(int ix, int iy, int h, int motion, StateId* next) const {
  if (motion < 8) {
    const int nx = ix + kOctileSteps[motion].dx, ny = iy + kOctileSteps[motion].dy;
    if (nx < 0 || ny < 0 || nx >= size_x_ || ny >= size_y_) return false;
    *next = StateOf(nx, ny, h);
    return true;
  }
  const int nh = motion == kTurnCounterClockwise ? (h + 1) % heading_count_ : (h + heading_count_ - 1) % heading_count_;
  *next = StateOf(ix, iy, nh);
  return true;
}

StateId FootprintStateSpace::Predecessor(StateId s, std::uint8_t motion) const {
  const int ix = CellX(s), iy = CellY(s), h = Heading(s);
  if (motion < 8) return StateOf(ix - kOctileSteps[motion].dx, iy - kOctileSteps[motion].dy, h);
  const int from =
      motion == kTurnCounterClockwise ? (h + heading_count_ - 1) % heading_count_ : (h + 1) % heading_count_;
  return StateOf(ix, iy, from);
}

const CellStencil& FootprintStateSpace::SweepExtra(int h, std::uint8_t motion) const {
  if (motion < 8) return stencils_.translation_extra(h, motion);
  // Both turns between h and h + 1 sweep the region stored at h.
  return motion == kTurnCounterClockwise ? stencils_.rotation_extra(h)
                                         : stencils_.rotation_extra((h + heading_count_ - 1) % heading_count_);
}

void FootprintStateSpace::KeepCollisionFree(int ix, int iy, int h, Motions* candidates) {
  collision_queries_ += candidates->count;
  if (mode_ == FootprintCheckMode::kPerExpansion) {
    batch_poses_.resize(candidates->count);
    batch_collides_.resize(candidates->count);
    for (int i = 0; i < candidates->count; ++i) {
      const StateId next = candidates->items[i].next;
      batch_poses_[i] = stencils_.PoseAt(CellX(next), CellY(next), Heading(next));
    }
    if (candidates->count > 0) checker_->CheckPoses(batch_poses_.data(), candidates->count, batch_collides_.data());
  }
  int kept = 0;
  for (int i = 0; i < candidates->count; ++i) {
    const Motion m = candidates->items[i];
    const bool end_free =
        mode_ == FootprintCheckMode::kPrecomputed ? cspace_->free_states()[m.next] != 0 : batch_collides_[i] == 0;
    if (!end_free || !blocks_.StencilIsFree(SweepExtra(h, m.motion), ix, iy)) continue;
    candidates->items[kept++] = m;
  }
  candidates->count = kept;
}

}  // namespace rc
