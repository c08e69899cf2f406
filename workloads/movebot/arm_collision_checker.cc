#include "workloads/movebot/arm_collision_checker.h"

#include <stdexcept>
#include <string>

namespace rc {

ArmCollisionChecker::ArmCollisionChecker(const LocobotArm& arm, const ArmScene& scene, CollisionOptions<double> options)
    : arm_(arm), scene_(scene), options_(options), sweep_radii_(arm.SweepRadii()), work_(scene.NewBatch()) {
  std::string error;
  if (!options_.sact.IsValid(&error)) throw std::invalid_argument("SACT options: " + error);
}

std::vector<bool> ArmCollisionChecker::Collides(const std::vector<ArmConfiguration>& configurations, double sweep_rad) {
  std::vector<Obbd> obbs;
  obbs.reserve(configurations.size() * kArmLinkBoxes);
  for (const ArmConfiguration& q : configurations) {
    const auto links = arm_.LinkObbs(q);
    for (int k = 0; k < kArmLinkBoxes; ++k) {
      obbs.push_back(links[k]);
      if (sweep_rad > 0) obbs.back().half.array() += sweep_radii_[k] * sweep_rad;
    }
  }
  const std::uint64_t visits_before = work_.visits.size();
  const std::uint64_t queries_before = work_.query_count();
  const std::vector<bool> link_collides = scene_.Collide(obbs, options_, work_);
  std::vector<bool> out(configurations.size(), false);
  for (std::size_t i = 0; i < link_collides.size(); ++i)
    if (link_collides[i]) out[i / kArmLinkBoxes] = true;
  for (CollisionWorkCounters* c : {&since_take_, &totals_}) {
    c->configurations += configurations.size();
    c->queries += work_.query_count() - queries_before;
    c->nodes += work_.visits.size() - visits_before;
  }
  return out;
}

CollisionBatch ArmCollisionChecker::TakeWork() {
  CollisionBatch taken = std::move(work_);
  work_ = scene_.NewBatch();
  return taken;
}

CollisionWorkCounters ArmCollisionChecker::TakeCounters() {
  const CollisionWorkCounters taken = since_take_;
  since_take_ = {};
  return taken;
}

}  // namespace rc
