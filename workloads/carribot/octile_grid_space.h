#pragma once
// The point robot's state space: one state per cell of an 8-connected octile
// grid. Straight moves cost 1, diagonal moves sqrt(2) (cells), and a diagonal
// needs both orthogonal neighbours free (no corner cutting), the MovingAI
// benchmark rules. Only free cells are passable; occupied and unknown cells
// and the outside of the map are blocked.
//
// States are indices of a copy of the grid padded by one blocked cell on every
// side, so neighbours never need a bounds check. Memory: 1 byte per padded
// cell; the search adds 13 bytes per padded cell (best_first_search.h).
#include <cstdint>
#include <vector>

#include "maps/occupancy_grid.h"
#include "workloads/carribot/indexed_min_heap.h"
#include "workloads/carribot/octile_steps.h"

namespace rc {

class OctileGridSpace {
 public:
  explicit OctileGridSpace(const OccupancyGrid& grid);

  std::size_t state_count() const { return passable_.size(); }
  int size_x() const { return size_x_; }
  int size_y() const { return size_y_; }

  StateId StateOf(int ix, int iy) const { return static_cast<StateId>((ix + 1) * padded_y_ + (iy + 1)); }
  int CellX(StateId s) const { return static_cast<int>(s / padded_y_) - 1; }
  int CellY(StateId s) const { return static_cast<int>(s % padded_y_) - 1; }
  bool IsPassable(int ix, int iy) const {
    return ix >= 0 && iy >= 0 && ix < size_x_ && iy < size_y_ && passable_[StateOf(ix, iy)] != 0;
  }

  // Sets the goal for Heuristic() and IsGoal(); resets the query counters.
  void SetGoal(int gx, int gy);
  // Successor validity checks (one per motion to a non-closed cell, the
  // corner cells of a diagonal included) since SetGoal.
  std::uint64_t collision_queries() const { return collision_queries_; }

  double Heuristic(StateId s) const { return OctileDistance(CellX(s) - goal_x_, CellY(s) - goal_y_); }
  bool IsGoal(StateId s) const { return s == goal_; }

  template <class IsClosed, class Visit>
  void ExpandValid(StateId s, const IsClosed& closed, const Visit& visit) {
    const int to_goal_x = CellX(s) - goal_x_, to_goal_y = CellY(s) - goal_y_;
    for (int d = 0; d < 8; ++d) {
      const StateId next = static_cast<StateId>(s + offset_[d]);
      if (closed(next)) continue;
      ++collision_queries_;
      if (!passable_[next]) continue;
      // No corner cutting: both cells beside a diagonal must be free.
      if (IsDiagonalStep(d) && (!passable_[s + offset_[(d + 7) % 8]] || !passable_[s + offset_[(d + 1) % 8]])) continue;
      visit(next, OctileStepCost(d), static_cast<std::uint8_t>(d),
            OctileDistance(to_goal_x + kOctileSteps[d].dx, to_goal_y + kOctileSteps[d].dy));
    }
  }
  StateId Predecessor(StateId s, std::uint8_t motion) const { return static_cast<StateId>(s - offset_[motion]); }

 private:
  int size_x_ = 0;
  int size_y_ = 0;
  int padded_y_ = 0;
  std::vector<std::uint8_t> passable_;
  std::int64_t offset_[8] = {};
  int goal_x_ = 0;
  int goal_y_ = 0;
  StateId goal_ = 0;
  std::uint64_t collision_queries_ = 0;
};

}  // namespace rc
