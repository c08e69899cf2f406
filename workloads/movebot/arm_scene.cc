#include "workloads/movebot/arm_scene.h"

namespace rc {

ArmScene ArmScene::FromObstacles(const std::vector<Obstacle>& obstacles) {
  std::vector<std::vector<Aabbd>> boxes;
  std::vector<SceneFrame> frames;
  for (const Obstacle& o : obstacles) {
    std::size_t f = 0;
    while (f < frames.size() && frames[f].rotation != o.box.axes) ++f;  // exact equality only
    if (f == frames.size()) {
      frames.emplace_back();
      frames.back().rotation = o.box.axes;
      frames.back().identity = o.box.axes == Eigen::Matrix3d::Identity();
      boxes.emplace_back();
    }
    Aabbd box;
    box.centre = frames[f].identity ? o.box.centre : Eigen::Vector3d(o.box.axes.transpose() * o.box.centre);
    box.half = o.box.half;
    boxes[f].push_back(box);
  }
  for (std::size_t f = 0; f < frames.size(); ++f) frames[f].tree = BuildMedianSplitTree(std::move(boxes[f]));
  ArmScene scene;
  scene.Lay(std::move(frames));
  return scene;
}

ArmScene ArmScene::FromBoxTree(BoxTree tree) {
  std::vector<SceneFrame> frames;
  if (!tree.nodes.empty()) {
    frames.emplace_back();
    frames.back().tree = std::move(tree);
  }
  ArmScene scene;
  scene.Lay(std::move(frames));
  return scene;
}

void ArmScene::Lay(std::vector<SceneFrame> frames) {
  frames_ = std::move(frames);
  node_count_ = 0;
  for (SceneFrame& f : frames_) {
    f.flat = FlatBoxTree<double>(f.tree);
    f.node_offset = static_cast<std::uint32_t>(node_count_);
    node_count_ += f.flat.nodes().size();
  }
}

std::size_t ArmScene::box_count() const {
  std::size_t n = 0;
  for (const SceneFrame& f : frames_) n += f.tree.boxes.size();
  return n;
}

CollisionBatch ArmScene::NewBatch() const {
  CollisionBatch batch;
  batch.node_bytes = FlatBoxTree<double>::node_bytes();
  batch.node_count = node_count_;
  return batch;
}

std::vector<bool> ArmScene::Collide(const std::vector<Obbd>& obbs, const CollisionOptions<double>& options,
                                    CollisionBatch& batch) const {
  std::vector<bool> collides(obbs.size(), false);
  std::vector<std::uint32_t> pending;  // the traversal's, allocated once per batch
  for (std::size_t i = 0; i < obbs.size(); ++i) {
    for (const SceneFrame& f : frames_) {
      Obbd local = obbs[i];
      if (!f.identity) {
        local.centre = f.rotation.transpose() * obbs[i].centre;
        local.axes = f.rotation.transpose() * obbs[i].axes;
      }
      const std::size_t first = batch.visits.size();
      TraversalOutcome outcome = CollideObb(f.flat, local, options, &batch.visits, &pending);
      for (std::size_t k = first; k < batch.visits.size(); ++k) batch.visits[k].node += f.node_offset;
      batch.outcomes.push_back(outcome);
      batch.visit_offsets.push_back(batch.visits.size());
      collides[i] = collides[i] || outcome.collides;
    }
  }
  return collides;
}

}  // namespace rc
