#pragma once
// Configurations of the arm against the scene, in batches: forward
// kinematics gives 4 link OBBs per configuration, and the whole batch's
// OBBs go to the collision kernel as one CollisionBatch (every query is a
// link OBB against one scene frame, arm_scene.h). Every batch is appended
// to a work log that the planner's timeline takes once per row, so each
// row prices exactly the kernel work of its iterations. Unless told not
// to (RoWild's arm tests none), the batch also tests the link boxes
// against each other, one query per configuration in the same launch
// (arm_self_collision.h), whatever the scene answered, as a thread per
// query would (the planner's tree, and so its later batches, do depend on
// the choice).
//
// Not thread-safe (OMPL's RRTstar calls it from one thread).
#include <array>
#include <cstdint>
#include <vector>

#include "robocore/collision/tree_collision.h"
#include "workloads/movebot/arm_scene.h"
#include "workloads/movebot/arm_self_collision.h"
#include "workloads/movebot/locobot_arm.h"

namespace rc {

struct CollisionWorkCounters {
  std::uint64_t configurations = 0;   // arm configurations checked
  std::uint64_t queries = 0;          // kernel queries: link OBB x scene frame, and one per configuration for its pairs
  std::uint64_t nodes = 0;            // node fetches (one SACT each)
  std::uint64_t self_tests = 0;       // of those, link-box pairs tested (up to the first overlap)
  std::uint64_t self_collisions = 0;  // configurations refused for self-collision (grown boxes on edges)
  std::uint64_t self_only = 0;        // of those, the ones clear of the scene
};

class ArmCollisionChecker {
 public:
  ArmCollisionChecker(const LocobotArm& arm, const ArmScene& scene, CollisionOptions<double> options = {},
                      SelfCollisionCheck self = SelfCollisionCheck::kOn);

  // One kernel batch; returns, per configuration, whether any link overlaps
  // an obstacle or (when checked) another link (touching counts). With
  // sweep_rad > 0 every link box is grown by SweepRadii()[k] * sweep_rad in
  // each half extent: it then contains everything the link sweeps while the
  // configuration moves up to sweep_rad (joint-space distance) along a
  // straight line from it; against each other, each pair's second box is
  // grown by its SelfSweepRadii entry * sweep_rad instead
  // (arm_self_collision.h).
  std::vector<bool> Collides(const std::vector<ArmConfiguration>& configurations, double sweep_rad = 0.0);
  bool Collides(const ArmConfiguration& q) { return Collides(std::vector<ArmConfiguration>{q}).front(); }

  // The kernel work since the last take (the scene's nodes, then the
  // self-collision nodes when checked; possibly no query), and its
  // counters; both restart from zero.
  CollisionBatch TakeWork();
  CollisionWorkCounters TakeCounters();
  const CollisionWorkCounters& totals() const { return totals_; }

  const LocobotArm& arm() const { return arm_; }
  const ArmScene& scene() const { return scene_; }
  bool checks_self_collision() const { return self_check_ == SelfCollisionCheck::kOn; }
  // The first pair of q's link boxes that overlap each other (none found
  // when self-collision is not checked); counts nothing.
  SelfCollision SelfCollisionOf(const ArmConfiguration& q) const;

 private:
  CollisionBatch NewBatch() const;

  const LocobotArm& arm_;
  const ArmScene& scene_;
  CollisionOptions<double> options_;
  SelfCollisionCheck self_check_;
  std::array<double, kArmLinkBoxes> sweep_radii_;
  std::vector<double> self_sweep_radii_;  // m/rad, per self-collision pair
  SelfCollisionKernel self_kernel_;
  CollisionBatch work_;
  CollisionWorkCounters since_take_, totals_;
};

}  // namespace rc
