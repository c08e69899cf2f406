#include "workloads/carribot/grid_planner.h"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "common/input_error.h"
#include "workloads/carribot/best_first_search.h"
#include "workloads/carribot/octile_grid_space.h"
#include "workloads/carribot/rasterized_footprint_checker.h"

namespace rc {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

std::string CellText(const GridPose& p) { return "(" + std::to_string(p.x) + ", " + std::to_string(p.y) + ")"; }

bool OutOfMap(const GridPose& p, int size_x, int size_y) {
  return p.x < 0 || p.y < 0 || p.x >= size_x || p.y >= size_y;
}

// Fills status, path, lengths and counters of `result` from one search.
// to_path_state(StateId) gives x, y, heading; motion_cost(motion) the edge cost.
template <class Space, class ToPathState, class MotionCost>
void SearchAndFill(Space& space, BestFirstSearch& search, const std::vector<StateId>& starts,
                   const PlannerOptions& options, double resolution_m, const ToPathState& to_path_state,
                   const MotionCost& motion_cost, PlanResult* result) {
  SearchCounters counters;
  StateId goal = 0;
  const SearchOutcome outcome =
      search.Run(space, starts, options.heuristic_weight, options.max_expansions, &goal, &counters);
  result->expanded = counters.expanded;
  result->generated = counters.generated;
  result->collision_queries = space.collision_queries();
  if (outcome == SearchOutcome::kExhausted) {
    result->status = PlanStatus::kNoPath;
    result->message = "goal unreachable: no collision-free path exists";
    return;
  }
  if (outcome == SearchOutcome::kExpansionLimit) {
    result->status = PlanStatus::kExpansionLimit;
    result->message = "expansion limit of " + std::to_string(options.max_expansions) + " reached";
    return;
  }
  result->status = PlanStatus::kFound;
  double cost = 0.0;
  for (const StateId s : search.PathTo(space, goal)) {
    const std::uint8_t motion = search.parent_motion(s);
    if (motion != BestFirstSearch::kStartMotion) {
      const double step = motion_cost(motion);
      cost += step;
      if (motion < 8)
        result->translation_cells += step;
      else
        ++result->turns;
    }
    PathState state = to_path_state(s);
    state.cost_cells = cost;
    result->path.push_back(state);
  }
  result->length_cells = cost;
  result->length_m = cost * resolution_m;
}

class PointRobotPlanner final : public GridPlanner {
 public:
  PointRobotPlanner(const OccupancyGrid& grid, const PlannerOptions& options)
      : options_(options), space_(grid), search_(space_.state_count()) {}

  double turn_cost_cells() const override { return 0.0; }
  int heading_count() const override { return 0; }

  PlanResult Plan(const GridPose& start, const GridPose& goal) override {
    if (start.heading != kAnyHeading || goal.heading != kAnyHeading)
      throw std::invalid_argument("a point robot has no heading");
    const auto t0 = Clock::now();
    PlanResult result;
    if (Rejected(start, goal, &result)) return result;
    space_.SetGoal(goal.x, goal.y);
    SearchAndFill(
        space_, search_, {space_.StateOf(start.x, start.y)}, options_, resolution_m_,
        [&](StateId s) {
          return PathState{space_.CellX(s), space_.CellY(s), kAnyHeading, 0.0};
        },
        [](std::uint8_t motion) { return OctileStepCost(motion); }, &result);
    result.wall_s = SecondsSince(t0);
    return result;
  }

 private:
  bool Rejected(const GridPose& start, const GridPose& goal, PlanResult* r) const {
    if (OutOfMap(start, space_.size_x(), space_.size_y())) {
      r->status = PlanStatus::kStartOutOfMap;
      r->message = "start " + CellText(start) + " is outside the map";
    } else if (OutOfMap(goal, space_.size_x(), space_.size_y())) {
      r->status = PlanStatus::kGoalOutOfMap;
      r->message = "goal " + CellText(goal) + " is outside the map";
    } else if (!space_.IsPassable(start.x, start.y)) {
      r->status = PlanStatus::kStartInCollision;
      r->message = "start cell " + CellText(start) + " is not free";
    } else if (!space_.IsPassable(goal.x, goal.y)) {
      r->status = PlanStatus::kGoalInCollision;
      r->message = "goal cell " + CellText(goal) + " is not free";
    } else {
      return false;
    }
    return true;
  }

  PlannerOptions options_;
  OctileGridSpace space_;
  BestFirstSearch search_;
};

class FootprintRobotPlanner final : public GridPlanner {
 public:
  FootprintRobotPlanner(const OccupancyGrid& grid, const PlannerOptions& options, FootprintChecker* checker)
      : options_(options),
        own_checker_(checker == nullptr && options.footprint->check_mode == FootprintCheckMode::kPerExpansion
                         ? std::make_unique<RasterizedFootprintChecker>(grid)
                         : nullptr),
        stencils_(options.footprint->length_m / grid.resolution_m(), options.footprint->width_m / grid.resolution_m(),
                  options.footprint->heading_count),
        space_(grid, stencils_, options.footprint->check_mode, checker != nullptr ? checker : own_checker_.get()),
        search_(space_.state_count()),
        size_x_(grid.size_x()),
        size_y_(grid.size_y()) {}

  double turn_cost_cells() const override { return space_.turn_cost_cells(); }
  int heading_count() const override { return space_.heading_count(); }

  PlanResult Plan(const GridPose& start, const GridPose& goal) override {
    CheckHeading(start.heading, "start");
    CheckHeading(goal.heading, "goal");
    const auto t0 = Clock::now();
    PlanResult result;
    std::vector<StateId> starts;
    if (!Rejected(start, goal, &starts, &result)) {
      space_.SetGoal(goal.x, goal.y, goal.heading);
      SearchAndFill(
          space_, search_, starts, options_, resolution_m_,
          [&](StateId s) {
            return PathState{space_.CellX(s), space_.CellY(s), space_.Heading(s), 0.0};
          },
          [&](std::uint8_t motion) { return space_.MotionCost(motion); }, &result);
    }
    result.wall_s = SecondsSince(t0);
    return result;
  }

 private:
  void CheckHeading(int heading, const char* which) const {
    if (heading != kAnyHeading && (heading < 0 || heading >= space_.heading_count()))
      throw std::invalid_argument(std::string(which) + " heading " + std::to_string(heading) + " is outside [0, " +
                                  std::to_string(space_.heading_count()) + ")");
  }

  // Free headings of a pose (all when heading is kAnyHeading).
  std::vector<int> FreeHeadings(const GridPose& p) {
    std::vector<int> free;
    for (int h = 0; h < space_.heading_count(); ++h)
      if ((p.heading == kAnyHeading || p.heading == h) && space_.IsPoseFree(p.x, p.y, h)) free.push_back(h);
    return free;
  }

  bool Rejected(const GridPose& start, const GridPose& goal, std::vector<StateId>* starts, PlanResult* r) {
    const auto in_collision = [](const char* which, const GridPose& p) {
      return std::string(which) + " " + CellText(p) +
             (p.heading == kAnyHeading ? ": the footprint collides at every heading"
                                       : ": the footprint collides at heading " + std::to_string(p.heading));
    };
    if (OutOfMap(start, size_x_, size_y_)) {
      r->status = PlanStatus::kStartOutOfMap;
      r->message = "start " + CellText(start) + " is outside the map";
      return true;
    }
    if (OutOfMap(goal, size_x_, size_y_)) {
      r->status = PlanStatus::kGoalOutOfMap;
      r->message = "goal " + CellText(goal) + " is outside the map";
      return true;
    }
    for (const int h : FreeHeadings(start)) starts->push_back(space_.StateOf(start.x, start.y, h));
    if (starts->empty()) {
      r->status = PlanStatus::kStartInCollision;
      r->message = in_collision("start", start);
      return true;
    }
    if (FreeHeadings(goal).empty()) {
      r->status = PlanStatus::kGoalInCollision;
      r->message = in_collision("goal", goal);
      return true;
    }
    return false;
  }

  PlannerOptions options_;
  std::unique_ptr<RasterizedFootprintChecker> own_checker_;
  FootprintStencils stencils_;
  FootprintStateSpace space_;
  BestFirstSearch search_;
  int size_x_;
  int size_y_;
};

}  // namespace

const char* ToString(PlanStatus status) {
  switch (status) {
    case PlanStatus::kFound: return "found";
    case PlanStatus::kNoPath: return "no_path";
    case PlanStatus::kStartOutOfMap: return "start_out_of_map";
    case PlanStatus::kGoalOutOfMap: return "goal_out_of_map";
    case PlanStatus::kStartInCollision: return "start_in_collision";
    case PlanStatus::kGoalInCollision: return "goal_in_collision";
    case PlanStatus::kExpansionLimit: return "expansion_limit";
  }
  return "unknown";
}

bool PlannerOptions::IsValid(std::string* error) const {
  if (!(heuristic_weight >= 1.0) || !std::isfinite(heuristic_weight)) {
    *error = "heuristic weight must be a finite number >= 1, got " + std::to_string(heuristic_weight);
    return false;
  }
  if (footprint) {
    const RectangleFootprint& f = *footprint;
    if (!(f.width_m >= 0) || !(f.length_m >= 0) || !std::isfinite(f.width_m) || !std::isfinite(f.length_m)) {
      *error = "footprint width and length must be finite and >= 0 m";
      return false;
    }
    if (f.heading_count < FootprintStencils::kMinHeadings || f.heading_count > FootprintStencils::kMaxHeadings) {
      *error = "heading count must be in [" + std::to_string(FootprintStencils::kMinHeadings) + ", " +
               std::to_string(FootprintStencils::kMaxHeadings) + "], got " + std::to_string(f.heading_count);
      return false;
    }
  }
  return true;
}

std::unique_ptr<GridPlanner> GridPlanner::Create(const OccupancyGrid& grid, const PlannerOptions& options,
                                                 FootprintChecker* checker) {
  std::string error;
  if (!options.IsValid(&error)) throw UsageError(error);
  const auto t0 = Clock::now();
  std::unique_ptr<GridPlanner> planner;
  if (options.footprint)
    planner = std::make_unique<FootprintRobotPlanner>(grid, options, checker);
  else
    planner = std::make_unique<PointRobotPlanner>(grid, options);
  planner->resolution_m_ = grid.resolution_m();
  planner->setup_wall_s_ = SecondsSince(t0);
  return planner;
}

}  // namespace rc
