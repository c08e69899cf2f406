#include "workloads/movebot/arm_self_collision.h"

#include <string>

#include "robocore/collision/aabb.h"

namespace rc {

SelfCollision FindSelfCollision(const std::array<Obbd, kArmLinkBoxes>& links, const ArmDescription& arm,
                                const SactOptions<double>& options, const std::vector<double>& growth_m) {
  SelfCollision out;
  for (std::size_t p = 0; p < arm.self_collision_pairs.size(); ++p) {
    const auto [first, second] = arm.self_collision_pairs[p];
    ++out.tests;
    Aabbd frame_box;  // the first box, in its own frame
    frame_box.half = links[first].half;
    Obbd moving = InFrameOf(links[second], links[first]);
    if (!growth_m.empty()) moving.half.array() += growth_m[p];
    if (TestObbAabb(moving, frame_box, options).overlaps()) {
      out.first = first;
      out.second = second;
      return out;
    }
  }
  return out;
}

std::vector<double> SelfSweepGrowth(const LocobotArm& arm, double sweep_rad) {
  std::vector<double> growth;
  for (const auto& [first, second] : arm.description().self_collision_pairs)
    growth.push_back(arm.SweepRadius(second, arm.description().links[first].frame) * sweep_rad);
  return growth;
}

std::string DescribeLinkPair(const ArmDescription& arm, int first, int second) {
  return "link " + std::to_string(first) + " (" + arm.links[first].name + ") and link " + std::to_string(second) +
         " (" + arm.links[second].name + ")";
}

}  // namespace rc
