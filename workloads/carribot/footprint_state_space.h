#pragma once
// The state space of a rectangular robot on a grid: states (x, y, heading)
// with the footprint centred on cell (x, y), and the motions of
// footprint_stencils.h (8 translations keeping the heading, 2 turns in place).
//
// Edge costs, in cells:
//  - translation: 1 straight, sqrt(2) diagonal, as for the point robot;
//  - turn by one heading step: the arc a footprint corner travels,
//    half_diagonal * 2*pi / headings. A point footprint turns for free, so
//    its path costs are exactly the octile optimum.
// Heuristic: the octile distance to the goal cell, plus, when the goal
// heading is fixed, the fewest turns times the turn cost. Each term is a
// lower bound of the cost still to pay and changes by at most the cost of
// one edge, so the heuristic is consistent.
//
// Collision checking, one query per motion whose target is not closed:
//  - kPrecomputed: the target pose is read from a ConfigurationSpace built up
//    front (exact; one byte per state): by the checker, one query per cell
//    and heading, when one is given (a collision kernel), else from the
//    footprint stencils;
//  - kPerExpansion: the targets of one expansion go to a FootprintChecker as
//    one batch (the plug-in point of a collision kernel).
// In both modes the cells the motion sweeps beyond its end footprints are then
// checked against the grid (cell_stencil.h), so the whole motion is
// collision-free. Both modes return identical paths.
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "maps/occupancy_grid.h"
#include "workloads/carribot/cell_stencil.h"
#include "workloads/carribot/configuration_space.h"
#include "workloads/carribot/footprint_checker.h"
#include "workloads/carribot/footprint_stencils.h"
#include "workloads/carribot/indexed_min_heap.h"

namespace rc {

enum class FootprintCheckMode { kPrecomputed, kPerExpansion };

class FootprintStateSpace {
 public:
  static constexpr int kAnyHeading = -1;
  static constexpr std::uint8_t kTurnCounterClockwise = 8;  // motion ids 0-7 are octile steps
  static constexpr std::uint8_t kTurnClockwise = 9;

  // The stencils and (kPerExpansion) the checker must outlive the space. In
  // kPrecomputed mode a checker, if given, fills the configuration space.
  // Throws std::invalid_argument for a null checker in kPerExpansion, or a
  // map too large for 32-bit state ids.
  FootprintStateSpace(const OccupancyGrid& grid, const FootprintStencils& stencils, FootprintCheckMode mode,
                      FootprintChecker* checker);

  std::size_t state_count() const { return static_cast<std::size_t>(size_x_) * size_y_ * heading_count_; }
  int heading_count() const { return heading_count_; }
  double turn_cost_cells() const { return turn_cost_; }
  FootprintCheckMode mode() const { return mode_; }

  StateId StateOf(int ix, int iy, int heading) const {
    return static_cast<StateId>((static_cast<std::size_t>(ix) * size_y_ + iy) * heading_count_ + heading);
  }
  int CellX(StateId s) const { return static_cast<int>(s / heading_count_ / size_y_); }
  int CellY(StateId s) const { return static_cast<int>(s / heading_count_ % size_y_); }
  int Heading(StateId s) const { return static_cast<int>(s % heading_count_); }

  // Validity of one pose through the active mode (counts as a query).
  bool IsPoseFree(int ix, int iy, int heading);

  // Sets the goal (heading kAnyHeading: any); resets the query counter.
  void SetGoal(int gx, int gy, int goal_heading);
  std::uint64_t collision_queries() const { return collision_queries_; }

  double Heuristic(StateId s) const;
  bool IsGoal(StateId s) const {
    return CellX(s) == goal_x_ && CellY(s) == goal_y_ && (goal_heading_ == kAnyHeading || Heading(s) == goal_heading_);
  }

  template <class IsClosed, class Visit>
  void ExpandValid(StateId s, const IsClosed& closed, const Visit& visit) {
    const int ix = CellX(s), iy = CellY(s), h = Heading(s);
    Motions candidates;
    for (int d = 0; d < 10; ++d) {
      StateId next;
      if (!Target(ix, iy, h, d, &next) || closed(next)) continue;
      candidates.items[candidates.count++] = {next, static_cast<std::uint8_t>(d)};
    }
    KeepCollisionFree(ix, iy, h, &candidates);
    for (int i = 0; i < candidates.count; ++i)
      visit(candidates.items[i].next, MotionCost(candidates.items[i].motion), candidates.items[i].motion,
            Heuristic(candidates.items[i].next));
  }
  StateId Predecessor(StateId s, std::uint8_t motion) const;

  double MotionCost(std::uint8_t motion) const;

 private:
  struct Motion {
    StateId next;
    std::uint8_t motion;
  };
  struct Motions {
    std::array<Motion, 10> items;
    int count = 0;
  };

  // The state `motion` leads to from (ix, iy, h); false if it leaves the map.
  bool Target(int ix, int iy, int h, int motion, StateId* next) const;
  void KeepCollisionFree(int ix, int iy, int h, Motions* candidates);
  const CellStencil& SweepExtra(int h, std::uint8_t motion) const;

  int size_x_ = 0;
  int size_y_ = 0;
  int heading_count_ = 0;
  const FootprintStencils& stencils_;
  FootprintCheckMode mode_;
  FootprintChecker* checker_ = nullptr;
  double turn_cost_ = 0.0;
  ColumnBlockIndex blocks_;
  std::unique_ptr<ConfigurationSpace> cspace_;  // kPrecomputed only
  std::vector<FootprintPose> batch_poses_;
  std::vector<std::uint8_t> batch_collides_;
  int goal_x_ = 0;
  int goal_y_ = 0;
  int goal_heading_ = kAnyHeading;
  std::uint64_t collision_queries_ = 0;
};

}  // namespace rc
