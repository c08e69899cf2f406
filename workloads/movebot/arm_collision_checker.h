#pragma once
// Configurations of the arm against the scene, in batches: forward
// kinematics gives 4 link OBBs per configuration, and the whole batch's
// OBBs go to the collision kernel as one CollisionBatch (every query is a
// link OBB against one scene frame, arm_scene.h). Every batch is appended
// to a work log that the planner's timeline takes once per row, so each
// row prices exactly the kernel work of its iterations.
//
// Not thread-safe (OMPL's RRTstar calls it from one thread).
#include <array>
#include <cstdint>
#include <vector>

#include "robocore/collision/tree_collision.h"
#include "workloads/movebot/arm_scene.h"
#include "workloads/movebot/locobot_arm.h"

namespace rc {

struct CollisionWorkCounters {
  std::uint64_t configurations = 0;  // arm configurations checked
  std::uint64_t queries = 0;         // link-OBB x frame queries sent to the kernel
  std::uint64_t nodes = 0;           // node fetches (one SACT each)
};

class ArmCollisionChecker {
 public:
  ArmCollisionChecker(const LocobotArm& arm, const ArmScene& scene, CollisionOptions<double> options = {});

  // One kernel batch; returns, per configuration, whether any link overlaps
  // an obstacle (touching counts). With sweep_rad > 0 every link box is
  // grown by SweepRadii()[k] * sweep_rad in each half extent: it then
  // contains everything the link sweeps while the configuration moves up
  // to sweep_rad (joint-space distance) along a straight line from it.
  std::vector<bool> Collides(const std::vector<ArmConfiguration>& configurations, double sweep_rad = 0.0);
  bool Collides(const ArmConfiguration& q) { return Collides(std::vector<ArmConfiguration>{q}).front(); }

  // The kernel work since the last take (the scene's layout, possibly no
  // query), and its counters; both restart from zero.
  CollisionBatch TakeWork();
  CollisionWorkCounters TakeCounters();
  const CollisionWorkCounters& totals() const { return totals_; }

  const LocobotArm& arm() const { return arm_; }
  const ArmScene& scene() const { return scene_; }

 private:
  const LocobotArm& arm_;
  const ArmScene& scene_;
  CollisionOptions<double> options_;
  std::array<double, kArmLinkBoxes> sweep_radii_;
  CollisionBatch work_;
  CollisionWorkCounters since_take_, totals_;
};

}  // namespace rc
