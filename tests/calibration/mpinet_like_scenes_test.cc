// The paper-scale SACT scenes (backends/calibration/mpinet_like_scenes.h):
// every scene's octree lands in the 1000-2000-node range at the first
// ladder step that reaches 1000 nodes; the voxels cover the scene's boxes;
// the queries are the poses aimed across the scene, pose-major and
// deterministic.
#include <cmath>

#include <gtest/gtest.h>

#include "backends/calibration/mpinet_like_scenes.h"
#include "robocore/collision/tree_collision.h"

namespace rc {
namespace {

TEST(MpinetLikeScenes, OctreesHave1000To2000NodesAtTheFirstLadderStepThatReaches1000) {
  for (MpinetSceneKind kind : kMpinetSceneKinds) {
    const SceneOctree octree = BuildSceneOctree(kind, 7);
    EXPECT_GE(octree.octree_nodes, kMinOctreeNodes) << ToString(kind);
    EXPECT_LE(octree.octree_nodes, kMaxOctreeNodes) << ToString(kind);
    const double coarser = octree.resolution_m * std::pow(2.0, 0.25);
    if (coarser <= kCoarsestResolution * 1.0001) {
      EXPECT_LT(VoxelizeScene(MakeMpinetLikeScene(kind, 7), coarser).octree_nodes, kMinOctreeNodes) << ToString(kind);
    }
    // The box tree holds every occupied leaf, so it has more nodes than cells.
    EXPECT_GT(octree.tree.nodes.size(), octree.octree_nodes) << ToString(kind);
  }
}

// Every scene box's centre lies in an occupied voxel (a 0.1 mm cube there
// collides), and one far above the scene does not. Not a bare point: a box
// centre can sit exactly on the face between two occupied voxels (the table
// top's does), where the separating-axis test's touching case is a tie.
TEST(MpinetLikeScenes, VoxelsCoverTheScenesBoxes) {
  const std::vector<Aabbd> boxes = MakeMpinetLikeScene(MpinetSceneKind::kTabletop, 3);
  const SceneOctree octree = VoxelizeScene(boxes, 0.02);
  const FlatBoxTree<double> tree(octree.tree);
  auto collides = [&](const Eigen::Vector3d& robot_frame_point) {
    Obbd probe;
    probe.centre = robot_frame_point - octree.offset_m;
    probe.half = Eigen::Vector3d::Constant(1e-4);
    return CollideObb(tree, probe, CollisionOptions<double>{}).collides;
  };
  for (const Aabbd& b : boxes) EXPECT_TRUE(collides(b.centre));
  EXPECT_FALSE(collides({0.7, 0.0, 3.0}));
  EXPECT_THROW(VoxelizeScene({}, 0.02), std::invalid_argument);
  EXPECT_THROW(VoxelizeScene(boxes, 0.0), std::invalid_argument);
}

// The same seed gives the same scene and queries from every compiler: a
// call's arguments are evaluated in an unspecified order (GCC and clang
// differ), so draws must not share one call. The pinned values are the
// scenes the GCC build has always made; the clang (sanitizer) build checks
// them too.
TEST(MpinetLikeScenes, SameSeedSameSceneFromEveryCompiler) {
  const std::vector<Aabbd> boxes = MakeMpinetLikeScene(MpinetSceneKind::kTabletop, 7);
  ASSERT_GE(boxes.size(), 6u);
  const Aabbd& first_object = boxes[5];  // after the table top and its four legs
  EXPECT_NEAR(first_object.centre.x(), 1.0383068877733255, 1e-12);
  EXPECT_NEAR(first_object.centre.y(), -0.25393833465779769, 1e-12);
  EXPECT_NEAR(first_object.half.x(), 0.027390022170929826, 1e-12);
  EXPECT_NEAR(first_object.half.y(), 0.026364397181878753, 1e-12);
  EXPECT_NEAR(first_object.half.z(), 0.046427387886119394, 1e-12);
  const SceneOctree octree = BuildSceneOctree(MpinetSceneKind::kCubby, 7);
  Obbd link;
  link.half = {0.05, 0.05, 0.05};
  link.centre = {0.0, 0.6, 0.4};
  const Obbd q = JitteredArmQueries({{link}}, 1, octree, 11).front();
  EXPECT_NEAR(q.centre.x(), 0.11644794127604764, 1e-12);
  EXPECT_NEAR(q.centre.y(), 0.71196541075759245, 1e-12);
  EXPECT_NEAR(q.centre.z(), 0.38709279146477288, 1e-12);
  EXPECT_NEAR(q.axes(0, 1), 0.9997108875477444, 1e-12);
}

TEST(MpinetLikeScenes, QueriesArePosesAimedAcrossTheSceneAndDeterministic) {
  const SceneOctree octree = BuildSceneOctree(MpinetSceneKind::kCubby, 7);
  Obbd base, tip;
  base.half = {0.1, 0.1, 0.1};
  tip.half = {0.05, 0.05, 0.05};
  tip.centre = {0.0, 0.6, 0.4};  // azimuth 90 degrees before turning
  const std::vector<std::vector<Obbd>> poses = {{base, tip}, {tip}};
  const std::vector<Obbd> q = JitteredArmQueries(poses, 5, octree, 11);
  ASSERT_EQ(q.size(), 5u * 3u);
  EXPECT_EQ(q.size(), JitteredArmQueries(poses, 5, octree, 11).size());
  for (std::size_t i = 0; i < q.size(); ++i) EXPECT_EQ(q[i].centre, JitteredArmQueries(poses, 5, octree, 11)[i].centre);
  for (int k = 0; k < 5; ++k) {
    const Eigen::Vector3d robot_frame = q[static_cast<std::size_t>(3 * k + 1)].centre + octree.offset_m;
    const double azimuth = std::atan2(robot_frame.y(), robot_frame.x());
    EXPECT_GE(azimuth, octree.azimuth_lo_rad - 0.05);  // the jitter moves it by up to 2 cm at 0.6 m
    EXPECT_LE(azimuth, octree.azimuth_hi_rad + 0.05);
    EXPECT_NEAR(robot_frame.z(), 0.4, 0.021);
  }
  EXPECT_THROW(JitteredArmQueries(poses, 0, octree, 1), std::invalid_argument);
  EXPECT_THROW(JitteredArmQueries({{}}, 1, octree, 1), std::invalid_argument);
}

}  // namespace
}  // namespace rc
