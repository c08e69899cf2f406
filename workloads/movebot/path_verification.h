#pragma once
// An independent check of a returned path: it shares no code with the
// collision kernel (no tree, no SACT). Every edge is re-checked at
// configurations spaced at most `resolution_rad` apart (finer than the
// planner's motion resolution), and at each configuration every link box
// is tested against every obstacle with the exact LP of
// robocore/collision/exact_overlap_reference.h (the link box expressed in
// the obstacle's own frame, where the obstacle is axis-aligned). A pair
// whose bounding spheres are apart (with a relative margin of 1e-9, far
// above rounding) skips the LP: disjoint spheres contain disjoint boxes.
// Touching counts as collision, as in the kernel. The joint limits are
// checked too, and unless told not to, the arm's self_collision_pairs
// against each other with the same LP (the second box in the first's
// frame).
#include <cstdint>
#include <string>
#include <vector>

#include "robocore/collision/obb.h"
#include "workloads/movebot/arm_self_collision.h"
#include "workloads/movebot/locobot_arm.h"

namespace rc {

struct PathVerification {
  bool ok = true;
  std::uint64_t configurations = 0;  // configurations checked
  std::uint64_t exact_tests = 0;     // LPs solved
  long edge = -1;                    // first bad edge (path[edge] -> path[edge + 1]); -1 if ok
  double t = 0.0;                    // where on that edge, in [0, 1]
  int link = -1;                     // colliding link box (0-based), -1 for a joint-limit violation
  long obstacle = -1;                // index into the obstacle list, -1 if none
  int other_link = -1;               // the link box it overlaps in a self-collision, -1 if none
  std::string message;               // empty if ok
};

// Throws std::invalid_argument unless resolution_rad > 0.
PathVerification VerifyPath(const LocobotArm& arm, const std::vector<Obbd>& obstacles,
                            const std::vector<ArmConfiguration>& path, double resolution_rad,
                            SelfCollisionCheck self = SelfCollisionCheck::kOn);

}  // namespace rc
