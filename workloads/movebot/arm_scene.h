#pragma once
// The MoveBot scene as the collision kernel sees it: trees of axis-aligned
// boxes (robocore/collision/box_tree.h), queried with link OBBs.
//
// Obstacles are oriented boxes (obstacle_file.h), but the kernel tests an
// OBB against AABBs only. So the scene groups the obstacles by rotation:
// obstacles with the same rotation R share one "frame", a tree of their
// boxes expressed in R's coordinates, where each is exactly an AABB
// (centre R^T c, the same half extents). A link OBB is expressed in each
// frame (centre R^T c_l, axes R^T A_l) and queried against that tree.
// This is exact: rotating both boxes by R^T changes neither whether they
// overlap nor anything else but rounding (the identity frame, which every
// obstacle of locobot_obs.txt is in, is not rotated at all). Rotations are
// grouped only when exactly equal, so no obstacle is ever approximated;
// a scene of n distinct rotations costs n tree queries per link.
// An OctoMap scene (--octree) is one identity frame: the occupied leaves.
//
// The frames' node arrays are laid out one after the other in the modelled
// device memory, so a batch of queries over all frames is one recorded
// CollisionBatch over one node region (what SactKernelRecord prices).
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "robocore/collision/box_tree.h"
#include "robocore/collision/flat_box_tree.h"
#include "robocore/collision/tree_collision.h"
#include "workloads/movebot/obstacle_file.h"

namespace rc {

struct SceneFrame {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // columns: the frame's axes in world
  bool identity = true;                                    // rotation is exactly I: no transform at all
  BoxTree tree;                                            // boxes in frame coordinates
  FlatBoxTree<double> flat;
  std::uint32_t node_offset = 0;  // first node's index in the scene's node array
};

class ArmScene {
 public:
  ArmScene() = default;
  static ArmScene FromObstacles(const std::vector<Obstacle>& obstacles);
  static ArmScene FromBoxTree(BoxTree tree);  // identity frame (an OctoMap's leaves)

  const std::vector<SceneFrame>& frames() const { return frames_; }
  std::uint64_t node_count() const { return node_count_; }
  std::size_t box_count() const;
  bool empty() const { return node_count_ == 0; }

  // Queries every OBB against every frame (obb-major: query i * frames + f),
  // appending the recorded visits to `batch` (node indices in the scene's
  // node array, so batch.Address() is the fetch address). Returns, per OBB,
  // whether it overlaps any obstacle (touching counts).
  std::vector<bool> Collide(const std::vector<Obbd>& obbs, const CollisionOptions<double>& options,
                            CollisionBatch& batch) const;
  // An empty batch with this scene's layout, to append to.
  CollisionBatch NewBatch() const;

 private:
  void Lay(std::vector<SceneFrame> frames);
  std::vector<SceneFrame> frames_;
  std::uint64_t node_count_ = 0;
};

}  // namespace rc
