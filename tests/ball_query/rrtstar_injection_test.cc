// The agreed injection: stock OMPL RRTstar with BackendNearestNeighbors set
// as its protected nn_ before setup(). Because every query answers exactly
// what NearestNeighborsLinear answers (same elements, same order), the same
// seeds must grow the same tree: same iterations, same best cost, same path,
// with k-nearest or radius rewiring and with tree pruning (which removes).
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/datastructures/NearestNeighborsLinear.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>
#include <ompl/util/Console.h>

#include "workloads/movebot/backend_nearest_neighbors.h"

namespace rc {
namespace {

namespace ob = ompl::base;
namespace og = ompl::geometric;

enum class Nn { kLinear, kPSphere, kPRay };

class SeededSampler final : public ob::RealVectorStateSampler {
 public:
  SeededSampler(const ob::StateSpace* space, std::uint32_t seed) : ob::RealVectorStateSampler(space) {
    rng_.setLocalSeed(seed);
  }
};

class InjectedRrtStar final : public og::RRTstar {
 public:
  InjectedRrtStar(const ob::SpaceInformationPtr& si, Nn which, std::uint32_t seed) : og::RRTstar(si) {
    if (which == Nn::kLinear) {
      nn_ = std::make_shared<ompl::NearestNeighborsLinear<Motion*>>();
    } else {
      BallQueryConfig config;
      config.formulation = which == Nn::kPRay ? BallQueryFormulation::kPRay : BallQueryFormulation::kPSphere;
      backend_ = std::make_shared<BackendNearestNeighbors<Motion*>>(
          config,
          [](Motion* const& m) -> const double* { return m->state->as<ob::RealVectorStateSpace::StateType>()->values; },
          si->getStateDimension());
      nn_ = backend_;
    }
    rng_.setLocalSeed(seed);
  }
  BallQueryCounters counters() const { return backend_ ? backend_->counters() : BallQueryCounters{}; }
  KernelRecord TakeKernelRecord() { return backend_ ? backend_->TakeKernelRecord() : KernelRecord{}; }

 private:
  std::shared_ptr<BackendNearestNeighbors<Motion*>> backend_;
};

struct Outcome {
  unsigned iterations = 0;
  double best_cost = 0;
  unsigned vertices = 0;
  std::vector<double> path;  // the solution's coordinates, state after state
  BallQueryCounters counters;
  std::size_t recorded_queries = 0;
};

// A 5-D joint box [-pi/2, pi/2]^5 with a cube obstacle |q_i| < 0.5 between
// start and goal.
Outcome Plan(Nn which, bool k_nearest, bool prune) {
  auto space = std::make_shared<ob::RealVectorStateSpace>(5);
  space->setBounds(-M_PI / 2, M_PI / 2);
  space->setStateSamplerAllocator([](const ob::StateSpace* s) { return std::make_shared<SeededSampler>(s, 2024); });
  auto si = std::make_shared<ob::SpaceInformation>(space);
  si->setStateValidityChecker([](const ob::State* s) {
    const double* q = s->as<ob::RealVectorStateSpace::StateType>()->values;
    for (int i = 0; i < 5; ++i)
      if (std::abs(q[i]) >= 0.5) return true;
    return false;
  });
  si->setStateValidityCheckingResolution(0.01);
  si->setup();
  ob::ScopedState<ob::RealVectorStateSpace> start(space), goal(space);
  for (int i = 0; i < 5; ++i) {
    start[i] = -1.2;
    goal[i] = 1.2;
  }
  auto pdef = std::make_shared<ob::ProblemDefinition>(si);
  pdef->setStartAndGoalStates(start, goal, 0.05);
  auto planner = std::make_shared<InjectedRrtStar>(si, which, 7);
  planner->setKNearest(k_nearest);
  planner->setTreePruning(prune);
  planner->setProblemDefinition(pdef);
  planner->setup();
  int checks = 0;
  const ob::PlannerStatus status =
      planner->solve(ob::PlannerTerminationCondition([&checks] { return ++checks > 800; }));
  EXPECT_TRUE(status == ob::PlannerStatus::EXACT_SOLUTION || status == ob::PlannerStatus::APPROXIMATE_SOLUTION);
  Outcome out;
  out.iterations = planner->numIterations();
  out.best_cost = planner->bestCost().value();
  ob::PlannerData data(si);
  planner->getPlannerData(data);
  out.vertices = data.numVertices();
  if (auto path = pdef->getSolutionPath())
    for (const ob::State* s : path->as<og::PathGeometric>()->getStates())
      for (int i = 0; i < 5; ++i) out.path.push_back(s->as<ob::RealVectorStateSpace::StateType>()->values[i]);
  out.counters = planner->counters();
  out.recorded_queries = planner->TakeKernelRecord().query_count();
  return out;
}

class RrtStarInjection : public testing::TestWithParam<std::pair<bool, bool>> {};

TEST_P(RrtStarInjection, SameTreeAsLinearOnTheSameSeeds) {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  const auto [k_nearest, prune] = GetParam();
  const Outcome linear = Plan(Nn::kLinear, k_nearest, prune);
  ASSERT_FALSE(linear.path.empty());
  EXPECT_GT(linear.vertices, 100u) << "the tree must grow for the comparison to mean something";
  RecordProperty("vertices", static_cast<int>(linear.vertices));
  RecordProperty("best_cost_rad", std::to_string(linear.best_cost));
  for (Nn which : {Nn::kPSphere, Nn::kPRay}) {
    const Outcome ours = Plan(which, k_nearest, prune);
    EXPECT_EQ(ours.iterations, linear.iterations);
    EXPECT_EQ(ours.best_cost, linear.best_cost);
    EXPECT_EQ(ours.vertices, linear.vertices);
    EXPECT_EQ(ours.path, linear.path);
    // Every planner query went through the kernel and into the record.
    EXPECT_GT(ours.counters.queries, ours.iterations);
    EXPECT_EQ(ours.recorded_queries, ours.counters.queries);
  }
}

INSTANTIATE_TEST_SUITE_P(Rewiring, RrtStarInjection,
                         testing::Values(std::make_pair(true, false), std::make_pair(false, false),
                                         std::make_pair(true, true)),
                         [](const testing::TestParamInfo<std::pair<bool, bool>>& info) {
                           return std::string(info.param.first ? "knearest" : "radius") +
                                  (info.param.second ? "_pruning" : "");
                         });

}  // namespace
}  // namespace rc
