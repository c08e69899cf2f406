#include "workloads/movebot/arm_collision_checker.h"

#include <stdexcept>
#include <string>

namespace rc {

ArmCollisionChecker::ArmCollisionChecker(const LocobotArm& arm, const ArmScene& scene, CollisionOptions<double> options,
                                         SelfCollisionCheck self_check)
    : arm_(arm),
      scene_(scene),
      options_(options),
      self_check_(self_check),
      sweep_radii_(arm.SweepRadii()),
      self_sweep_radii_(SelfSweepRadii(arm)),
      self_kernel_(arm, scene.node_count()),
      work_(NewBatch()) {
  std::string error;
  if (!options_.sact.IsValid(&error)) throw std::invalid_argument("SACT options: " + error);
}

std::vector<bool> ArmCollisionChecker::Collides(const std::vector<ArmConfiguration>& configurations, double sweep_rad) {
  std::vector<Obbd> obbs;
  obbs.reserve(configurations.size() * kArmLinkBoxes);
  std::vector<std::array<Obbd, kArmLinkBoxes>> links;
  links.reserve(configurations.size());
  std::uint64_t self_tests = 0, self_collisions = 0, self_only = 0;
  // Against each other, a link's sweep counts only the joints between the
  // two boxes (and only the second box grows, in the first's frame): the
  // growth against the scene would make neighbours' neighbours touch.
  std::vector<double> self_growth;  // m, per pair; none without a sweep
  if (sweep_rad > 0)
    for (double radius : self_sweep_radii_) self_growth.push_back(radius * sweep_rad);
  for (const ArmConfiguration& q : configurations) {
    links.push_back(arm_.LinkObbs(q));
    for (int k = 0; k < kArmLinkBoxes; ++k) {
      obbs.push_back(links.back()[k]);
      if (sweep_rad > 0) obbs.back().half.array() += sweep_radii_[k] * sweep_rad;
    }
  }
  const std::uint64_t visits_before = work_.visits.size();
  const std::uint64_t queries_before = work_.query_count();
  // The launch's queries: every link box against the scene, then each
  // configuration's pairs.
  const std::vector<bool> link_collides = scene_.Collide(obbs, options_, work_);
  std::vector<bool> out(configurations.size(), false);
  for (std::size_t i = 0; i < link_collides.size(); ++i)
    if (link_collides[i]) out[i / kArmLinkBoxes] = true;
  if (self_check_ == SelfCollisionCheck::kOn) {
    std::vector<std::uint32_t> pending;  // the traversal's, allocated once per batch
    for (std::size_t i = 0; i < configurations.size(); ++i) {
      const SelfCollision hit = self_kernel_.Collide(links[i], options_, self_growth, work_, &pending);
      self_tests += hit.tests;
      if (!hit.found()) continue;
      ++self_collisions;
      if (!out[i]) ++self_only;
      out[i] = true;
    }
  }
  for (CollisionWorkCounters* c : {&since_take_, &totals_}) {
    c->configurations += configurations.size();
    c->queries += work_.query_count() - queries_before;
    c->nodes += work_.visits.size() - visits_before;
    c->self_tests += self_tests;
    c->self_collisions += self_collisions;
    c->self_only += self_only;
  }
  return out;
}

SelfCollision ArmCollisionChecker::SelfCollisionOf(const ArmConfiguration& q) const {
  if (self_check_ == SelfCollisionCheck::kOff) return {};
  return FindSelfCollision(arm_.LinkObbs(q), arm_.description(), options_.sact);
}

CollisionBatch ArmCollisionChecker::NewBatch() const {
  CollisionBatch batch = scene_.NewBatch();
  if (self_check_ == SelfCollisionCheck::kOn) batch.node_count += self_kernel_.node_count();
  // Visits decided by a sphere pre-test ran no SACT stage: the batch says
  // so, and pricing refuses it (SactKernelRecord).
  batch.sphere_pretests = options_.sact.sphere_pretests;
  return batch;
}

CollisionBatch ArmCollisionChecker::TakeWork() {
  CollisionBatch taken = std::move(work_);
  work_ = NewBatch();
  return taken;
}

CollisionWorkCounters ArmCollisionChecker::TakeCounters() {
  const CollisionWorkCounters taken = since_take_;
  since_take_ = {};
  return taken;
}

}  // namespace rc
