#include "workloads/movebot/locobot_arm.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rc {

const ArmDescription& LocobotArmDescription() {
  static const ArmDescription arm = [] {
    ArmDescription a;
    // Frames: translation from the previous frame (m) and joint axis. RoWild
    // locobot.h rDesc (rpy all zero) and axis.
    a.frames = {{
        {{0.08, 0.0, 0.159}, {0, 0, 1}},         // base -> joint 1 (waist), about z
        {{0.0, 0.0, 0.04125}, {0, 1, 0}},        // joint 1 -> joint 2 (shoulder), about y
        {{0.05, 0.0, 0.2}, {0, 1, 0}},           // joint 2 -> joint 3 (elbow), about y
        {{0.2002, 0.0, 0.0}, {0, 1, 0}},         // joint 3 -> joint 4 (wrist pitch), about y
        {{0.063, 0.0001, 0.0}, {-1, 0, 0}},      // joint 4 -> joint 5 (wrist roll), about -x
        {{0.106525, 0.0, 0.0050143}, {0, 1, 0}}  // joint 5 -> end-effector centre (fixed)
    }};
    // Link boxes: frame index (RoWild cIdx), centre offset (cDesc xyz, rpy
    // all zero) and full size (cDim, "LWH").
    a.links = {{
        {1, {0.0, 0.0, 0.09}, {0.05, 0.05, 0.25}, "upper arm"},
        {2, {0.075, 0.0, 0.0}, {0.25, 0.05, 0.05}, "forearm"},
        {3, {0.027, -0.012, 0.0}, {0.07, 0.076, 0.05}, "wrist"},
        {4, {0.055, 0.0, 0.01}, {0.11, 0.11, 0.07}, "hand"},  // hand and gripper
    }};
    // Every pair of boxes not on neighbouring frames (locobot_arm.h says
    // why): the upper arm against the wrist and the hand, the forearm
    // against the hand.
    a.self_collision_pairs = {{0, 2}, {0, 3}, {1, 3}};
    a.joint_min_rad = -M_PI / 2;  // RoWild qMin; REFERENCE.md section 3
    a.joint_max_rad = M_PI / 2;
    a.source = "RoWild MoveBot (cmu-roboarch/rowild cpu/src/locobot/locobot.h, from the LoCoBot URDF)";
    return a;
  }();
  return arm;
}

LocobotArm::LocobotArm(const ArmDescription& description) : description_(description) {
  for (const auto& [first, second] : description_.self_collision_pairs)
    if (first < 0 || second < 0 || first >= kArmLinkBoxes || second >= kArmLinkBoxes ||
        description_.links[first].frame >= description_.links[second].frame)
      throw std::invalid_argument("self-collision pair (" + std::to_string(first) + ", " + std::to_string(second) +
                                  "): each box must exist, the second on a later frame than the first");
}

bool LocobotArm::WithinLimits(const ArmConfiguration& q, std::string* why) const {
  for (int j = 0; j < kArmJoints; ++j) {
    if (std::isfinite(q[j]) && q[j] >= joint_min() && q[j] <= joint_max()) continue;
    if (why)
      *why = "joint " + std::to_string(j + 1) + " = " + std::to_string(q[j]) + " rad is outside [" +
             std::to_string(joint_min()) + ", " + std::to_string(joint_max()) + "]";
    return false;
  }
  return true;
}

std::array<Eigen::Isometry3d, kArmFrames> LocobotArm::ForwardKinematics(const ArmConfiguration& q) const {
  std::array<Eigen::Isometry3d, kArmFrames> pose;
  Eigen::Isometry3d current = Eigen::Isometry3d::Identity();
  for (int i = 0; i < kArmFrames; ++i) {
    const ArmFrame& f = description_.frames[i];
    const double angle = i < kArmJoints ? q[i] : 0.0;
    current = current * Eigen::Translation3d(f.link_translation) * Eigen::AngleAxisd(angle, f.joint_axis);
    pose[i] = current;
  }
  return pose;
}

std::array<Obbd, kArmLinkBoxes> LocobotArm::LinkObbs(const ArmConfiguration& q) const {
  const auto pose = ForwardKinematics(q);
  std::array<Obbd, kArmLinkBoxes> out;
  for (int k = 0; k < kArmLinkBoxes; ++k) {
    const ArmLinkBox& box = description_.links[k];
    const Eigen::Isometry3d& frame = pose[box.frame];
    out[k].centre = frame * box.offset;
    out[k].axes = frame.linear();
    out[k].half = box.size / 2;
  }
  return out;
}

std::array<double, kArmLinkBoxes> LocobotArm::SweepRadii() const {
  std::array<double, kArmLinkBoxes> out{};
  for (int k = 0; k < kArmLinkBoxes; ++k) out[k] = SweepRadius(k, -1);
  return out;
}

double LocobotArm::SweepRadius(int k, int frame) const {
  const ArmLinkBox& box = description_.links[k];
  double sum_sq = 0;
  for (int j = std::max(frame + 1, 0); j <= box.frame && j < kArmJoints; ++j) {
    double r = box.offset.norm() + box.size.norm() / 2;
    for (int i = j + 1; i <= box.frame; ++i) r += description_.frames[i].link_translation.norm();
    sum_sq += r * r;
  }
  return std::sqrt(sum_sq);
}

}  // namespace rc
