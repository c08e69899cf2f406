#include "workloads/delibot/motion_model.h"

#include <cmath>

namespace rc {
namespace {

// Below this translation (m) the heading of the motion is noise; AMCL uses
// the same 1 cm cut-off.
constexpr double kNegligibleTranslationM = 0.01;

}  // namespace

OdometryDelta ComputeOdometryDelta(const Pose2& previous, const Pose2& current) {
  OdometryDelta d;
  const double dx = current.x - previous.x;
  const double dy = current.y - previous.y;
  d.trans = std::hypot(dx, dy);
  d.rot1 = d.trans < kNegligibleTranslationM ? 0.0 : WrapAngle(std::atan2(dy, dx) - previous.theta);
  d.rot2 = WrapAngle(current.theta - previous.theta - d.rot1);
  return d;
}

Pose2 SampleOdometryMotion(const Pose2& pose, const OdometryDelta& delta, const OdometryMotionNoise& noise,
                           RandomStream& stream) {
  // For backward motion, |rot1| is close to pi; the noise should scale with
  // the small angle between the motion and the reversed heading.
  const double rot1_for_noise = std::min(std::abs(delta.rot1), std::abs(WrapAngle(delta.rot1 - kPi)));
  const double rot2_for_noise = std::min(std::abs(delta.rot2), std::abs(WrapAngle(delta.rot2 - kPi)));
  const double t2 = delta.trans * delta.trans;
  const double sd_rot1 = std::sqrt(noise.alpha1 * rot1_for_noise * rot1_for_noise + noise.alpha2 * t2);
  const double sd_trans =
      std::sqrt(noise.alpha3 * t2 + noise.alpha4 * (rot1_for_noise * rot1_for_noise + rot2_for_noise * rot2_for_noise));
  const double sd_rot2 = std::sqrt(noise.alpha1 * rot2_for_noise * rot2_for_noise + noise.alpha2 * t2);
  const double rot1 = delta.rot1 - stream.Gaussian(sd_rot1);
  const double trans = delta.trans - stream.Gaussian(sd_trans);
  const double rot2 = delta.rot2 - stream.Gaussian(sd_rot2);
  Pose2 out;
  out.x = pose.x + trans * std::cos(pose.theta + rot1);
  out.y = pose.y + trans * std::sin(pose.theta + rot1);
  out.theta = WrapAngle(pose.theta + rot1 + rot2);
  return out;
}

}  // namespace rc
