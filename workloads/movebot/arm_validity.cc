#include "workloads/movebot/arm_validity.h"

#include <cmath>
#include <stdexcept>

#include <ompl/base/spaces/RealVectorStateSpace.h>

namespace rc {

ArmConfiguration ToArmConfiguration(const ompl::base::State* state) {
  const double* v = state->as<ompl::base::RealVectorStateSpace::StateType>()->values;
  ArmConfiguration q;
  for (int j = 0; j < kArmJoints; ++j) q[j] = v[j];
  return q;
}

ArmStateValidityChecker::ArmStateValidityChecker(const ompl::base::SpaceInformationPtr& si,
                                                 ArmCollisionChecker* checker)
    : ompl::base::StateValidityChecker(si), checker_(checker) {}

bool ArmStateValidityChecker::isValid(const ompl::base::State* state) const {
  if (!si_->satisfiesBounds(state)) return false;
  return !checker_->Collides(ToArmConfiguration(state));
}

ArmMotionValidator::ArmMotionValidator(const ompl::base::SpaceInformationPtr& si, ArmCollisionChecker* checker,
                                       double resolution_rad)
    : ompl::base::MotionValidator(si), checker_(checker), resolution_(resolution_rad) {
  if (!(resolution_rad > 0) || !std::isfinite(resolution_rad))
    throw std::invalid_argument("motion resolution must be a positive number of radians");
}

unsigned ArmMotionValidator::FirstCollision(const ompl::base::State* s1, const ompl::base::State* s2,
                                            unsigned* segments) const {
  const double distance = si_->distance(s1, s2);
  const unsigned n = std::max(1u, static_cast<unsigned>(std::ceil(distance / resolution_)));
  *segments = n;
  const ArmConfiguration a = ToArmConfiguration(s1), b = ToArmConfiguration(s2);
  // Checks at t = k/n, k = 0..n (s1 too: its grown boxes cover the first
  // half segment).
  std::vector<ArmConfiguration> checks(n + 1);
  for (unsigned k = 0; k <= n; ++k) {
    const double t = static_cast<double>(k) / n;
    for (int j = 0; j < kArmJoints; ++j) checks[k][j] = k == n ? b[j] : a[j] + t * (b[j] - a[j]);
  }
  // Every configuration of the edge is within distance / (2n) of a check.
  const std::vector<bool> collides = checker_->Collides(checks, distance / (2.0 * n));
  for (unsigned k = 0; k <= n; ++k)
    if (collides[k]) return std::max(k, 1u);
  return 0;
}

bool ArmMotionValidator::checkMotion(const ompl::base::State* s1, const ompl::base::State* s2) const {
  unsigned n = 0;
  const bool ok = si_->satisfiesBounds(s2) && FirstCollision(s1, s2, &n) == 0;
  if (ok)
    ++valid_;
  else
    ++invalid_;
  return ok;
}

bool ArmMotionValidator::checkMotion(const ompl::base::State* s1, const ompl::base::State* s2,
                                     std::pair<ompl::base::State*, double>& last_valid) const {
  unsigned n = 0;
  const unsigned first = si_->satisfiesBounds(s2) ? FirstCollision(s1, s2, &n) : 1;
  if (first == 0) {
    ++valid_;
    return true;
  }
  if (n == 0) n = 1;  // out of bounds: the whole edge after s1 is invalid
  last_valid.second = static_cast<double>(first - 1) / n;
  if (last_valid.first) si_->getStateSpace()->interpolate(s1, s2, last_valid.second, last_valid.first);
  ++invalid_;
  return false;
}

}  // namespace rc
