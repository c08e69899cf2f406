#include "workloads/movebot/arm_self_collision.h"

#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>

#include "robocore/collision/aabb.h"
#include "robocore/collision/box_tree.h"

namespace rc {

namespace {

void RequireOneGrowthPerPair(const std::vector<double>& growth_m, std::size_t pairs, const char* caller) {
  if (!growth_m.empty() && growth_m.size() != pairs)
    throw std::invalid_argument(std::string(caller) + ": one growth per self-collision pair, or none");
}

// Pair p's second box in its first box's frame, grown by its growth entry
// (if any): what the host search and the kernel's pass test against the
// first box.
Obbd SecondBoxInFirstFrame(const std::array<Obbd, kArmLinkBoxes>& links, std::pair<int, int> pair,
                           const std::vector<double>& growth_m, std::size_t p) {
  Obbd moving = InFrameOf(links[pair.second], links[pair.first]);
  if (!growth_m.empty()) moving.half.array() += growth_m[p];
  return moving;
}

}  // namespace

SelfCollision FindSelfCollision(const std::array<Obbd, kArmLinkBoxes>& links, const ArmDescription& arm,
                                const SactOptions<double>& options, const std::vector<double>& growth_m) {
  RequireOneGrowthPerPair(growth_m, arm.self_collision_pairs.size(), "FindSelfCollision");
  SelfCollision out;
  for (std::size_t p = 0; p < arm.self_collision_pairs.size(); ++p) {
    const auto [first, second] = arm.self_collision_pairs[p];
    ++out.tests;
    Aabbd frame_box;  // the first box, in its own frame
    frame_box.half = links[first].half;
    if (TestObbAabb(SecondBoxInFirstFrame(links, arm.self_collision_pairs[p], growth_m, p), frame_box, options)
            .overlaps()) {
      out.first = first;
      out.second = second;
      return out;
    }
  }
  return out;
}

SelfCollisionKernel::SelfCollisionKernel(const LocobotArm& arm, std::uint64_t first_node)
    : pairs_(arm.description().self_collision_pairs), first_node_(first_node) {
  tree_of_link_.fill(-1);
  for (const auto& pair : pairs_) {  // in range: LocobotArm checked them
    const int first = pair.first;
    if (tree_of_link_[first] >= 0) continue;
    Aabbd box;  // in its own frame: centred at the origin
    box.half = arm.description().links[first].size / 2;
    tree_of_link_[first] = static_cast<int>(trees_.size());
    trees_.emplace_back(BuildMedianSplitTree({box}));
  }
  if (!trees_.empty() && first_node_ + trees_.size() - 1 > std::uint64_t{UINT32_MAX})
    throw std::invalid_argument("SelfCollisionKernel: node indices beyond 32 bits");
}

SelfCollision SelfCollisionKernel::Collide(const std::array<Obbd, kArmLinkBoxes>& links,
                                           const CollisionOptions<double>& options,
                                           const std::vector<double>& growth_m, CollisionBatch& batch,
                                           std::vector<std::uint32_t>* pending) const {
  RequireOneGrowthPerPair(growth_m, pairs_.size(), "SelfCollisionKernel");
  SelfCollision out;
  TraversalOutcome query;
  for (std::size_t p = 0; p < pairs_.size() && !out.found(); ++p) {
    const auto [first, second] = pairs_[p];
    ++out.tests;
    const int tree = tree_of_link_[first];
    const std::size_t begin = batch.visits.size();
    const TraversalOutcome pass =
        CollideObb(trees_[tree], SecondBoxInFirstFrame(links, pairs_[p], growth_m, p), options, &batch.visits, pending);
    for (std::size_t k = begin; k < batch.visits.size(); ++k)
      batch.visits[k].node += static_cast<std::uint32_t>(first_node_ + tree);
    query.nodes_visited += pass.nodes_visited;
    query.last_exit = pass.last_exit;
    if (pass.collides) {
      query.collides = true;
      query.colliding_box = static_cast<std::uint32_t>(p);
      out.first = first;
      out.second = second;
    }
  }
  if (out.tests > 0) {
    batch.outcomes.push_back(query);
    batch.visit_offsets.push_back(batch.visits.size());
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
