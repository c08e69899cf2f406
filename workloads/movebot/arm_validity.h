#pragma once
// OMPL's two collision hooks for the arm, both answered by the collision
// kernel through ArmCollisionChecker (one kernel batch per call):
//   ArmStateValidityChecker  one configuration: in the joint limits and no
//                            link overlapping an obstacle;
//   ArmMotionValidator       a straight joint-space edge, checked at
//                            configurations spaced at most `resolution`
//                            (rad, Euclidean in joint space), all sent as
//                            ONE batch, as a GPU would run them. Each check
//                            grows the link boxes by what they can sweep
//                            within half a spacing (SweepRadii x
//                            spacing / 2), so every configuration between
//                            two checks is covered: an accepted edge is
//                            collision-free along its whole length, not
//                            only at the checks (without the growth, a
//                            fine independent check found edges that
//                            clipped an obstacle corner between checks).
// The edge's first state is checked too (grown), unlike OMPL's
// DiscreteMotionValidator, which assumes it valid.
#include <utility>

#include <ompl/base/MotionValidator.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/StateValidityChecker.h>

#include "workloads/movebot/arm_collision_checker.h"

namespace rc {

ArmConfiguration ToArmConfiguration(const ompl::base::State* state);

class ArmStateValidityChecker final : public ompl::base::StateValidityChecker {
 public:
  ArmStateValidityChecker(const ompl::base::SpaceInformationPtr& si, ArmCollisionChecker* checker);
  bool isValid(const ompl::base::State* state) const override;

 private:
  ArmCollisionChecker* checker_;
};

class ArmMotionValidator final : public ompl::base::MotionValidator {
 public:
  // Throws std::invalid_argument unless resolution_rad > 0 and finite.
  ArmMotionValidator(const ompl::base::SpaceInformationPtr& si, ArmCollisionChecker* checker, double resolution_rad);
  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2) const override;
  bool checkMotion(const ompl::base::State* s1, const ompl::base::State* s2,
                   std::pair<ompl::base::State*, double>& last_valid) const override;
  double resolution() const { return resolution_; }

 private:
  // Index (1..n) of the first colliding check of the edge, 0 if none; n
  // is the number of segments.
  unsigned FirstCollision(const ompl::base::State* s1, const ompl::base::State* s2, unsigned* segments) const;
  ArmCollisionChecker* checker_;
  double resolution_;
};

}  // namespace rc
