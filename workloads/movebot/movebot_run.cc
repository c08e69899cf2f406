#include "workloads/movebot/movebot_run.h"

#include <chrono>
#include <cmath>
#include <memory>
#include <stdexcept>

#include <omp.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/objectives/PathLengthOptimizationObjective.h>
#include <ompl/geometric/PathGeometric.h>

#include "backends/calibration/sact_kernel_record.h"
#include "workloads/movebot/arm_validity.h"
#include "workloads/movebot/movebot_rrtstar.h"

namespace rc {
namespace ob = ompl::base;

bool MoveBotSettings::IsValid(std::string* error) const {
  auto fail = [&](const std::string& why) {
    if (error) *error = why;
    return false;
  };
  if (iterations == 0 && !(time_limit_s > 0 && std::isfinite(time_limit_s)))
    return fail("give an iteration budget (> 0) or a time limit (> 0 s)");
  if (batch_iterations == 0) return fail("iterations per timeline row must be > 0");
  if (!(motion_resolution_rad > 0) || !std::isfinite(motion_resolution_rad))
    return fail("motion resolution must be > 0 rad");
  if (!(range_rad >= 0) || !std::isfinite(range_rad)) return fail("range must be >= 0 rad (0: OMPL's default)");
  if (!(goal_bias >= 0 && goal_bias <= 1)) return fail("goal bias must be in [0, 1]");
  return true;
}

const char* ToString(MoveBotStatus status) {
  switch (status) {
    case MoveBotStatus::kExact: return "exact";
    case MoveBotStatus::kApproximate: return "approximate";
    case MoveBotStatus::kNone: return "none";
  }
  return "?";
}

namespace {

std::string Describe(const ArmConfiguration& q) {
  std::string s = "(";
  for (int j = 0; j < kArmJoints; ++j) s += (j ? ", " : "") + std::to_string(q[j]);
  return s + ") rad";
}

void RequireEndpoint(ArmCollisionChecker& checker, const ArmConfiguration& q, const char* name) {
  std::string why;
  if (CheckEndpoint(checker, q, &why) != EndpointProblem::kNone)
    throw std::invalid_argument(std::string(name) + " " + Describe(q) + ": " + why);
}

}  // namespace

EndpointProblem CheckEndpoint(ArmCollisionChecker& checker, const ArmConfiguration& q, std::string* why) {
  if (!checker.arm().WithinLimits(q, why)) return EndpointProblem::kOutsideLimits;
  if (!checker.Collides(q)) return EndpointProblem::kNone;
  const SelfCollision hit = checker.SelfCollisionOf(q);
  if (hit.found()) {
    if (why)
      *why = "in self-collision: " + DescribeLinkPair(checker.arm().description(), hit.first, hit.second) + " overlap";
    return EndpointProblem::kSelfCollision;
  }
  if (why) *why = "in collision: a link box overlaps an obstacle";
  return EndpointProblem::kInCollision;
}

MoveBotResult RunMoveBot(ArmCollisionChecker& checker, const MoveBotSettings& settings) {
  std::string error;
  if (!settings.IsValid(&error)) throw std::invalid_argument(error);
  RequireEndpoint(checker, settings.start, "start");
  RequireEndpoint(checker, settings.goal, "goal");

  const LocobotArm& arm = checker.arm();
  auto space = std::make_shared<ob::RealVectorStateSpace>(kArmJoints);
  space->setBounds(arm.joint_min(), arm.joint_max());
  const std::uint32_t seed = settings.seed;
  space->setStateSamplerAllocator(
      [seed](const ob::StateSpace* s) { return std::make_shared<SeededRealVectorSampler>(s, seed); });
  auto si = std::make_shared<ob::SpaceInformation>(space);
  si->setStateValidityChecker(std::make_shared<ArmStateValidityChecker>(si, &checker));
  si->setMotionValidator(std::make_shared<ArmMotionValidator>(si, &checker, settings.motion_resolution_rad));
  si->setup();

  ob::ScopedState<ob::RealVectorStateSpace> start(space), goal(space);
  for (int j = 0; j < kArmJoints; ++j) {
    start[j] = settings.start[j];
    goal[j] = settings.goal[j];
  }
  auto pdef = std::make_shared<ob::ProblemDefinition>(si);
  pdef->setStartAndGoalStates(start, goal);
  auto objective = std::make_shared<ob::PathLengthOptimizationObjective>(si);
  objective->setCostThreshold(ob::Cost(0.0));  // never "good enough": use the whole budget
  pdef->setOptimizationObjective(objective);

  auto planner = std::make_shared<MoveBotRrtStar>(si, settings.nn, settings.seed);
  planner->setProblemDefinition(pdef);
  planner->setGoalBias(settings.goal_bias);
  if (settings.range_rad > 0) planner->setRange(settings.range_rad);
  planner->setup();

  MoveBotResult result;
  result.planner_name = planner->getName();
  result.self_collision_checked = checker.checks_self_collision();
  std::unique_ptr<BackendLedger> collision_ledger, nn_ledger;
  if (settings.price_backends) {
    collision_ledger = std::make_unique<BackendLedger>(settings.backend_params, settings.ledger);
    nn_ledger = std::make_unique<BackendLedger>(settings.backend_params, settings.ledger);
  }

  const auto t0 = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  auto budget_spent = [&] {
    return settings.iterations > 0 ? planner->numIterations() >= settings.iterations
                                   : elapsed() >= settings.time_limit_s;
  };
  long row_index = 0;
  while (!budget_spent()) {
    const std::uint64_t before = planner->numIterations();
    std::uint64_t target = before + settings.batch_iterations;
    if (settings.iterations > 0) target = std::min<std::uint64_t>(target, settings.iterations);
    const ob::PlannerTerminationCondition ptc([&] { return planner->numIterations() >= target || budget_spent(); });
    const ob::PlannerStatus status = planner->solve(ptc);
    if (status == ob::PlannerStatus::INVALID_START || status == ob::PlannerStatus::INVALID_GOAL ||
        status == ob::PlannerStatus::UNRECOGNIZED_GOAL_TYPE || status == ob::PlannerStatus::CRASH ||
        status == ob::PlannerStatus::ABORT)
      throw std::runtime_error(std::string("RRTstar: ") + status.asString());

    MoveBotRow row;
    row.row = row_index++;
    row.iterations = planner->numIterations();
    row.samples = row.iterations - before;
    row.time_s = elapsed();
    row.tree_states = planner->tree_size();
    row.collision = checker.TakeCounters();
    const CollisionBatch collision_work = checker.TakeWork();
    row.nn = planner->TakeNnWork();
    row.best_cost_rad = planner->bestCost().value();
    if (collision_ledger) {
      std::optional<KernelRecord> collision_record;
      // The ledger's address sample (--replay-sms, --replay-block-stride),
      // as every workload's records take it; exits tallied per query, which
      // prices the same as a byte per fetch with no profiling pass.
      if (collision_work.query_count() > 0)
        collision_record = SactKernelRecord(collision_work, nullptr, collision_ledger->RecordSample(),
                                            RecordedExits::kTallied);
      collision_ledger->BeginIteration();
      row.collision_pricing = collision_ledger->EndIteration(collision_record ? &*collision_record : nullptr);
      nn_ledger->BeginIteration();
      row.nn_pricing = nn_ledger->EndIteration(row.nn.record ? &*row.nn.record : nullptr);
      row.priced = true;
      // The planner's next batch runs on this thread alone, for far longer
      // than pricing's parallel loops. libgomp's idle workers would spin
      // through its start (GOMP_SPINCOUNT) and burn CPU that no work needs:
      // they are let go, and the next batch's pricing starts them again.
      omp_pause_resource_all(omp_pause_soft);
    }
    row.nn.record.reset();
    result.rows.push_back(std::move(row));
  }
  result.planning_s = elapsed();
  result.iterations = planner->numIterations();
  if (collision_ledger) {
    result.priced = true;
    result.collision_pricing = collision_ledger->Finish();
    result.nn_pricing = nn_ledger->Finish();
  }

  if (pdef->hasSolution()) {
    result.status = pdef->hasApproximateSolution() ? MoveBotStatus::kApproximate : MoveBotStatus::kExact;
    const auto path = pdef->getSolutionPath()->as<ompl::geometric::PathGeometric>();
    for (std::size_t i = 0; i < path->getStateCount(); ++i)
      result.path.push_back(ToArmConfiguration(path->getState(i)));
    result.path_cost_rad = path->length();
    result.goal_distance_rad = pdef->getSolutionDifference();
    if (result.status == MoveBotStatus::kExact) result.goal_distance_rad = 0.0;
  }
  return result;
}

}  // namespace rc
