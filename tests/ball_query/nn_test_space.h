#pragma once
// Random states of an OMPL RealVectorStateSpace for the nearest-neighbour
// tests: the structures are compared on OMPL's own distance.
#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <vector>

#include <ompl/base/spaces/RealVectorStateSpace.h>

namespace rc::test {

using State = ompl::base::State*;

class NnTestSpace {
 public:
  explicit NnTestSpace(unsigned dimension) : space_(std::make_shared<ompl::base::RealVectorStateSpace>(dimension)) {}
  ~NnTestSpace() {
    for (State s : states_) space_->freeState(s);
  }
  NnTestSpace(const NnTestSpace&) = delete;
  NnTestSpace& operator=(const NnTestSpace&) = delete;

  unsigned dimension() const { return space_->getDimension(); }
  // A state whose coordinates are uniform in [lo, hi), or rounded to a
  // grid of step `grid` when grid > 0 (many equal distances: ties).
  State Make(std::mt19937_64& rng, double lo, double hi, double grid = 0) {
    State s = space_->allocState();
    std::uniform_real_distribution<double> u(lo, hi);
    for (unsigned i = 0; i < dimension(); ++i) {
      double v = u(rng);
      if (grid > 0) v = grid * std::floor(v / grid);
      Values(s)[i] = v;
    }
    states_.push_back(s);
    return s;
  }
  static double* Values(State s) { return s->as<ompl::base::RealVectorStateSpace::StateType>()->values; }
  double Distance(State a, State b) const { return space_->distance(a, b); }

 private:
  std::shared_ptr<ompl::base::RealVectorStateSpace> space_;
  std::vector<State> states_;
};

}  // namespace rc::test
