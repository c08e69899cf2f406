#pragma once
// Odometry motion model (Thrun, Burgard, Fox, "Probabilistic Robotics",
// sample_motion_model_odometry), with AMCL's two corrections: a negligible
// translation has no meaningful direction, so its first rotation is zero;
// and backward motion is treated as a small rotation plus reverse
// translation, not a half turn.
//
// Every particle draws its own noise from its own stream; RoWild draws one
// sample for all particles, which collapses the set within a few updates.
#include "common/angles.h"
#include "common/random_stream.h"

namespace rc {

struct OdometryMotionNoise {
  double alpha1 = 0.05;  // rotation noise from rotation (rad^2/rad^2)
  double alpha2 = 0.05;  // rotation noise from translation (rad^2/m^2)
  double alpha3 = 0.1;   // translation noise from translation (m^2/m^2)
  double alpha4 = 0.05;  // translation noise from rotation (m^2/rad^2)
};

// Relative motion between two odometry poses, in the robot frame.
struct OdometryDelta {
  double rot1 = 0.0;   // rad
  double trans = 0.0;  // m
  double rot2 = 0.0;   // rad
  bool IsZero() const { return rot1 == 0.0 && trans == 0.0 && rot2 == 0.0; }
};

OdometryDelta ComputeOdometryDelta(const Pose2& previous, const Pose2& current);

// Applies the delta with noise drawn from `stream` to `pose` (map frame).
Pose2 SampleOdometryMotion(const Pose2& pose, const OdometryDelta& delta, const OdometryMotionNoise& noise,
                           RandomStream& stream);

}  // namespace rc
