#include "workloads/movebot/arm_self_collision.h"

#include <stdexcept>
#include <string>

#include "robocore/collision/aabb.h"

namespace rc {

SelfCollision FindSelfCollision(const std::array<Obbd, kArmLinkBoxes>& links, const ArmDescription& arm,
                                const SactOptions<double>& options, const std::vector<double>& growth_m) {
  if (!growth_m.empty() && growth_m.size() != arm.self_collision_pairs.size())
    throw std::invalid_argument("FindSelfCollision: one growth per self-collision pair, or none");
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

std::vector<double> SelfSweepRadii(const LocobotArm& arm) {
  std::vector<double> radii;
  for (const auto& [first, second] : arm.description().self_collision_pairs)
    radii.push_back(arm.SweepRadius(second, arm.description().links[first].frame));
  return radii;
}

std::string DescribeLinkPair(const ArmDescription& arm, int first, int second) {
  return "link " + std::to_string(first) + " (" + arm.links[first].name + ") and link " + std::to_string(second) +
         " (" + arm.links[second].name + ")";
}

}  // namespace rc
