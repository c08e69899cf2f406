#pragma once
// CarriBot's planner: A* or weighted A* from a start cell to a goal cell of an
// occupancy grid, for a point robot (octile_grid_space.h) or a rectangular
// robot with headings (footprint_state_space.h). Ceres-style: options with
// IsValid(), a Create() factory, and one final implementation per robot kind.
//
// A planner builds its state space once (and, for a footprint in
// kPrecomputed mode, the configuration space) and reuses its search arrays
// for every Plan() call, resetting only what the previous query touched.
//
// Outcomes are results, not exceptions: an unreachable goal is
// PlanStatus::kNoPath, a start or goal outside the map or in collision has
// its own status and message. Exceptions are for misuse (invalid options, a
// heading index out of range).
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "maps/occupancy_grid.h"
#include "workloads/carribot/footprint_checker.h"
#include "workloads/carribot/footprint_state_space.h"

namespace rc {

struct RectangleFootprint {
  double width_m = 0.0;   // across the heading, >= 0
  double length_m = 0.0;  // along the heading, >= 0
  int heading_count = 8;  // in [4, 64]; the CLI offers 8 and 16
  FootprintCheckMode check_mode = FootprintCheckMode::kPrecomputed;
};

struct PlannerOptions {
  double heuristic_weight = 1.0;                // >= 1; 1 = A* (optimal), w > 1 = weighted A* (cost <= w * optimal)
  std::optional<RectangleFootprint> footprint;  // unset: point robot on the octile grid
  std::uint64_t max_expansions = 0;             // 0 = no limit

  bool IsValid(std::string* error) const;
};

inline constexpr int kAnyHeading = FootprintStateSpace::kAnyHeading;

// A cell and (footprint robots) a heading index; kAnyHeading leaves it free:
// a start may then take any collision-free heading at no cost, and any
// heading at the goal cell ends the search.
struct GridPose {
  int x = 0;
  int y = 0;
  int heading = kAnyHeading;
};

enum class PlanStatus {
  kFound,
  kNoPath,  // the goal is unreachable
  kStartOutOfMap,
  kGoalOutOfMap,
  kStartInCollision,  // blocked cell, or no collision-free footprint heading there
  kGoalInCollision,
  kExpansionLimit,  // PlannerOptions::max_expansions reached first
};
// "found", "no_path", "start_out_of_map", ... (the timeline's status column).
const char* ToString(PlanStatus status);

struct PathState {
  int x = 0;
  int y = 0;
  int heading = kAnyHeading;  // kAnyHeading for a point robot
  double cost_cells = 0.0;    // cumulative cost from the start
};

struct PlanResult {
  PlanStatus status = PlanStatus::kNoPath;
  std::string message;             // one line for people; empty when found
  std::vector<PathState> path;     // start to goal; empty unless found
  double length_cells = 0.0;       // path cost (translations + turns), cells
  double length_m = 0.0;           // the same in metres (cells * resolution)
  double translation_cells = 0.0;  // the translations alone
  int turns = 0;                   // in-place heading steps
  std::uint64_t expanded = 0;
  std::uint64_t generated = 0;
  std::uint64_t collision_queries = 0;  // motions whose validity was checked
  double wall_s = 0.0;                  // this query, set-up excluded

  bool found() const { return status == PlanStatus::kFound; }
};

class GridPlanner {
 public:
  virtual ~GridPlanner() = default;

  // Throws UsageError for invalid options. `checker` is used, not owned, by a
  // footprint robot: in kPerExpansion mode it answers every expansion's
  // batch (null selects the exact RasterizedFootprintChecker); in
  // kPrecomputed mode it fills the configuration space, one query per cell
  // and heading (null: the exact stencils do). The grid is copied; it need
  // not outlive the planner.
  static std::unique_ptr<GridPlanner> Create(const OccupancyGrid& grid, const PlannerOptions& options,
                                             FootprintChecker* checker = nullptr);

  // Throws std::invalid_argument for a heading index outside [0, headings)
  // (or any heading but kAnyHeading for a point robot).
  virtual PlanResult Plan(const GridPose& start, const GridPose& goal) = 0;

  // Footprint half diagonal * 2 pi / headings; 0 for a point robot.
  virtual double turn_cost_cells() const = 0;
  virtual int heading_count() const = 0;  // 0 for a point robot
  // Set-up time in Create (state space, stencils, configuration space).
  double setup_wall_s() const { return setup_wall_s_; }
  double resolution_m() const { return resolution_m_; }

 protected:
  double setup_wall_s_ = 0.0;
  double resolution_m_ = 1.0;
};

}  // namespace rc
