#pragma once
// OMPL's RRTstar, unchanged, with two things set before its own setup():
// the nearest-neighbour structure (motion_nearest_neighbors.h) and the
// seed of its goal-bias generator. Nothing of the algorithm is overridden:
// setup() assigns the protected nn_ and rng_ and then calls
// RRTstar::setup(), which keeps an nn_ that is already set.
//
// Why seed here: ompl::RNG::setSeed takes effect only before the first RNG
// of the process is created, so a second run in the same process (tests,
// the comparison study) would otherwise not repeat. With the planner's
// rng_ and the state sampler (SeededRealVectorSampler) seeded locally,
// the same seed gives the same tree in any process.
#include <cstdint>
#include <functional>

#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>

#include "workloads/movebot/motion_nearest_neighbors.h"

namespace rc {

class SeededRealVectorSampler final : public ompl::base::RealVectorStateSampler {
 public:
  SeededRealVectorSampler(const ompl::base::StateSpace* space, std::uint32_t seed)
      : ompl::base::RealVectorStateSampler(space) {
    rng_.setLocalSeed(seed);
  }
};

class MoveBotRrtStar final : public ompl::geometric::RRTstar {
 public:
  MoveBotRrtStar(const ompl::base::SpaceInformationPtr& si, NnKind nn_kind, std::uint32_t seed)
      : ompl::geometric::RRTstar(si), nn_kind_(nn_kind), seed_(seed) {
    setName(std::string("RRTstar_") + ToString(nn_kind));
  }

  void setup() override {
    if (!nn_) {
      const unsigned dimension = si_->getStateDimension();
      NnHandle<Motion*> handle = MakeNearestNeighbors<Motion*>(
          nn_kind_, this,
          [](Motion* const& m) -> const double* {
            return m->state->as<ompl::base::RealVectorStateSpace::StateType>()->values;
          },
          dimension);
      nn_ = handle.nn;
      take_ = handle.take;
      rng_.setLocalSeed(seed_);
    }
    RRTstar::setup();
  }

  // NN work since the last take (setup() must have run).
  NnWork TakeNnWork() { return take_ ? take_() : NnWork{}; }
  std::size_t tree_size() const { return nn_ ? nn_->size() : 0; }

 private:
  NnKind nn_kind_;
  std::uint32_t seed_;
  std::function<NnWork()> take_;
};

}  // namespace rc
