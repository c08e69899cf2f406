#pragma once
// The MoveBot robot: a LoCoBot-like 5-DoF arm (the WidowX-style arm on
// PyRobot's LoCoBot), its forward kinematics (Eigen) and its four link
// boxes as OBBs (robocore/collision/obb.h).
//
// Every number that defines the arm lives in LocobotArmDescription() below,
// in one place, with its source: RoWild's MoveBot (cmu-roboarch/rowild,
// cpu/src/locobot/locobot.h, MIT licence), whose frames it says come from
// the LoCoBot URDF. REFERENCE.md section 3: 5 revolute joints in
// [-pi/2, pi/2], 4 link OBBs from forward kinematics.
//
// Frame chain: F_0 = Link_0 * Rot(axis_0, q_0), F_i = F_{i-1} * Link_i *
// Rot(axis_i, q_i). Link_i is a fixed translation (every link rotation of
// the URDF is zero); frame 5 is the end-effector centre and has no joint
// (q_5 = 0). A link box sits in frame `frame` at `offset`, axis-aligned with
// that frame, with FULL dimensions `size` (RoWild's blockDescToBoundingBox
// halves them).
//
// Self-collision: the link boxes of self_collision_pairs are tested against
// each other (arm_self_collision.h); RoWild tests none.
// Not modelled (as in RoWild): the gripper fingers, and the base, which is
// an obstacle in the scene file instead ("Base and mount" in
// locobot_obs.txt).
#include <array>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "robocore/collision/obb.h"

namespace rc {

inline constexpr int kArmJoints = 5;
inline constexpr int kArmFrames = 6;  // 5 joints + the end-effector frame
inline constexpr int kArmLinkBoxes = 4;

using ArmConfiguration = std::array<double, kArmJoints>;  // rad

struct ArmFrame {
  Eigen::Vector3d link_translation;  // m, from the previous frame (the base for frame 0)
  Eigen::Vector3d joint_axis;        // unit, in this frame
};

struct ArmLinkBox {
  int frame = 0;           // the frame the box moves with
  Eigen::Vector3d offset;  // m, box centre in that frame
  Eigen::Vector3d size;    // m, FULL dimensions along the frame's x, y, z
  std::string name;        // what messages call it
};

struct ArmDescription {
  std::array<ArmFrame, kArmFrames> frames;
  std::array<ArmLinkBox, kArmLinkBoxes> links;
  // The pairs of link boxes (indices into links, first < second) that must
  // not overlap each other. Boxes on neighbouring frames of the chain are
  // left out, as a MoveIt SRDF disables adjacent links: whether they
  // overlap does not depend on the configuration (the upper arm and
  // forearm, and the forearm and wrist, overlap or touch at their joint;
  // the wrist and hand turn about their common axis 1 mm apart). Each
  // pair's second box lies on a later frame than its first (LocobotArm's
  // constructor checks), which the sweep bound of an edge check needs.
  std::vector<std::pair<int, int>> self_collision_pairs;
  double joint_min_rad = 0;
  double joint_max_rad = 0;
  std::string source;
};

// The LoCoBot arm, with the numbers and the source described above.
const ArmDescription& LocobotArmDescription();

class LocobotArm {
 public:
  // Throws std::invalid_argument when a self-collision pair names a box
  // out of range, or its second box is not on a later frame than its first.
  explicit LocobotArm(const ArmDescription& description = LocobotArmDescription());

  const ArmDescription& description() const { return description_; }
  double joint_min() const { return description_.joint_min_rad; }  // rad
  double joint_max() const { return description_.joint_max_rad; }  // rad
  // True when every joint lies in [joint_min, joint_max]; otherwise `why`
  // names the first joint outside (1-based, as the CLI prints them).
  bool WithinLimits(const ArmConfiguration& q, std::string* why = nullptr) const;

  // World (base) poses of the 6 frames.
  std::array<Eigen::Isometry3d, kArmFrames> ForwardKinematics(const ArmConfiguration& q) const;
  // The 4 link boxes in the world frame.
  std::array<Obbd, kArmLinkBoxes> LinkObbs(const ArmConfiguration& q) const;
  // Per link box, a bound R_k (m/rad) on how far any of its points moves
  // when the configuration moves a joint-space distance d along a straight
  // line: at most R_k * d. A point p moves at sum_j |dq_j| |p - o_j| at
  // most (o_j on joint j's axis), so R_k = sqrt(sum_j r_j^2) by
  // Cauchy-Schwarz, with r_j the largest distance from joint j's origin to
  // the box (the chained link lengths plus offset and half diagonal).
  std::array<double, kArmLinkBoxes> SweepRadii() const;
  // The same bound in the coordinates of frame `frame` (which turns with
  // joints 0..frame; -1: the base, as SweepRadii): only the joints after
  // it move box k there. What box k sweeps relative to a box on that frame.
  double SweepRadius(int k, int frame) const;

 private:
  ArmDescription description_;
};

}  // namespace rc
