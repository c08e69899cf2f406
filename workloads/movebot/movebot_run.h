#pragma once
// One MoveBot planning run: OMPL's RRTstar (movebot_rrtstar.h) on a
// RealVectorStateSpace(5) with the joint limits as bounds, path length in
// joint space (rad) as the objective, the kernel-backed validity checker
// and motion validator (arm_validity.h), run in batches of iterations.
// After every batch, one timeline row: what the batch sampled and queried,
// and the batch's recorded kernel work priced on every modelled backend
// (collision: SACT record; NN: the ball-query kernel's record when the
// structure is a backend one), with the chosen backend from the scheduler
// ledger (one ledger per kernel: each kernel is scheduled on its own
// counter).
//
// Termination: the iteration budget, or the time budget (checked every
// iteration; a time budget is not repeatable across machines, an
// iteration budget is). The cost threshold is 0, so RRTstar never stops at
// its first solution: it improves the path for the whole budget.
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "backends/backend_params.h"
#include "backends/scheduler/backend_ledger.h"
#include "workloads/movebot/arm_collision_checker.h"
#include "workloads/movebot/motion_nearest_neighbors.h"

namespace rc {

struct MoveBotSettings {
  ArmConfiguration start{};              // rad
  ArmConfiguration goal{};               // rad
  std::uint64_t iterations = 0;          // RRTstar iterations; 0: use time_limit_s
  double time_limit_s = 0.0;             // s; used when iterations == 0
  std::uint64_t batch_iterations = 100;  // iterations per timeline row
  double motion_resolution_rad = 0.02;   // edge check spacing (Euclidean in joint space)
  double range_rad = 0.0;                // RRTstar's range; 0: OMPL's own default
  double goal_bias = 0.05;               // RRTstar's default
  std::uint32_t seed = 1;
  NnKind nn = NnKind::kGnat;
  bool price_backends = true;
  BackendParameters backend_params;
  LedgerOptions ledger;

  bool IsValid(std::string* error) const;
};

enum class MoveBotStatus { kExact, kApproximate, kNone };
const char* ToString(MoveBotStatus status);

struct MoveBotRow {
  long row = 0;
  std::uint64_t iterations = 0;  // cumulative
  std::uint64_t samples = 0;     // this row (one per iteration)
  double time_s = 0.0;           // cumulative planning wall time
  std::uint64_t tree_states = 0;
  CollisionWorkCounters collision;  // this row
  NnWork nn;                        // this row (record dropped once priced)
  double best_cost_rad = std::numeric_limits<double>::infinity();
  bool priced = false;
  LedgerIteration collision_pricing, nn_pricing;
};

struct MoveBotResult {
  MoveBotStatus status = MoveBotStatus::kNone;
  std::vector<ArmConfiguration> path;  // start .. goal (or closest state) for exact/approximate
  double path_cost_rad = std::numeric_limits<double>::infinity();
  double goal_distance_rad = std::numeric_limits<double>::infinity();  // 0 for exact
  std::vector<MoveBotRow> rows;
  std::uint64_t iterations = 0;
  double planning_s = 0.0;
  std::string planner_name;
  bool priced = false;
  LedgerSummary collision_pricing, nn_pricing;
  bool self_collision_checked = false;  // the checker tested link boxes against each other
};

// Why `q` cannot be a start or goal, for the caller to report as its own
// kind of error before planning: kOutsideLimits (a joint beyond the arm's
// limits, or not finite), kSelfCollision (two of its link boxes overlap,
// when the checker tests that), kInCollision (a link box overlaps an
// obstacle of the scene), the first that applies in that order. `why`
// says which joint, which links, or that it collides.
enum class EndpointProblem { kNone, kOutsideLimits, kSelfCollision, kInCollision };
EndpointProblem CheckEndpoint(ArmCollisionChecker& checker, const ArmConfiguration& q, std::string* why);

// Throws std::invalid_argument naming the problem when the settings are
// invalid, or when start or goal has an EndpointProblem (both checked
// before planning; callers that tell a user check them first).
MoveBotResult RunMoveBot(ArmCollisionChecker& checker, const MoveBotSettings& settings);

}  // namespace rc
