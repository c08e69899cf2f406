#pragma once
// Rigid 2-D pose composition, for chaining odometry: the simulator builds
// odometry from true motion with it, and the localizer replays recent
// odometry backwards to check an injected pose against past scans.
#include <cmath>

#include "common/angles.h"

namespace rc {

// a (+) b: b expressed in a's frame, composed onto a.
inline Pose2 Compose(const Pose2& a, const Pose2& b) {
  const double c = std::cos(a.theta), s = std::sin(a.theta);
  return {a.x + c * b.x - s * b.y, a.y + s * b.x + c * b.y, WrapAngle(a.theta + b.theta)};
}

// a^-1 (+) b: the motion from a to b in a's frame.
inline Pose2 Between(const Pose2& a, const Pose2& b) {
  const double c = std::cos(a.theta), s = std::sin(a.theta);
  const double dx = b.x - a.x, dy = b.y - a.y;
  return {c * dx + s * dy, -s * dx + c * dy, WrapAngle(b.theta - a.theta)};
}

}  // namespace rc
