#pragma once
// Paper-scale SACT workloads: scenes like the four MPiNet task scenes the
// RoboGPU paper collides against (cubby, merged cubby, dresser, tabletop;
// REFERENCE.md section 2: octrees of 1261-1557 nodes), voxelized with
// OctoMap into octrees of 1000-2000 nodes, and batches of at least 10,000
// robot-link OBBs.
//
// The scenes are ours, modelled from the scene kinds' descriptions, never
// from the artifact's octree data: axis-aligned boards and objects in front
// of a robot base at the origin (z up), within the arm's reach.
//
// Node count. The artifact's octree node is a cell holding up to eight child
// boxes, the root being the scene's bounding box. Ours counts the same
// thing: the OctoMap cells that have children, in the subtree of the
// smallest cell that holds every occupied leaf (the octree is built in the
// scene's frame, lower corner at the origin, so that cell is the scene's).
// The resolution is the coarsest of a ladder (kCoarsestResolution x
// 2^(-k/4), k = 0, 1, ...) whose octree has at least kMinOctreeNodes cells;
// a ladder step changes the count by about 2^(1/2) (surfaces), so the first
// count at or above 1000 is below 2000 (checked, and a scene that jumps
// past kMaxOctreeNodes is an error). The box tree the kernels fetch
// (robocore/collision/octree_from_octomap.h) has one box per node, so it
// holds more nodes than that count (every occupied leaf is a node); both
// numbers are reported.
//
// Queries. The 10 arm poses of mpnet_master_obb.csv (7 link OBBs each), or,
// without it, seeded random OBBs of link size (each its own pose); each pose
// turned about the base's vertical axis so that its last link points at
// `yaws` evenly spaced azimuths across the scene's extent as seen from the
// base (a planner's poses reach into the scene), and each link jittered by
// a seeded 2 cm per axis and 0.05 rad about a random axis; pose-major (a
// pose's links are consecutive queries, as a planner checks them). In the
// octree's frame (the scene's offset subtracted).
#include <cstdint>
#include <string>
#include <vector>

#include "robocore/collision/aabb.h"
#include "robocore/collision/box_tree.h"
#include "robocore/collision/obb.h"

namespace rc {

enum class MpinetSceneKind : std::uint8_t { kCubby, kMergedCubby, kDresser, kTabletop };
const char* ToString(MpinetSceneKind kind);  // "cubby", "merged cubby", "dresser", "tabletop"
inline constexpr MpinetSceneKind kMpinetSceneKinds[] = {MpinetSceneKind::kCubby, MpinetSceneKind::kMergedCubby,
                                                        MpinetSceneKind::kDresser, MpinetSceneKind::kTabletop};

// The scene's boxes in the robot's frame (m). Deterministic for a seed.
std::vector<Aabbd> MakeMpinetLikeScene(MpinetSceneKind kind, std::uint64_t seed);

// The resolution ladder and the node range (see the top of this file).
inline constexpr double kCoarsestResolution = 0.08;  // m
inline constexpr int kResolutionSteps = 16;          // down to 0.08 / 16 = 5 mm
inline constexpr std::uint32_t kMinOctreeNodes = 1000;
inline constexpr std::uint32_t kMaxOctreeNodes = 2000;

struct SceneOctree {
  MpinetSceneKind kind = MpinetSceneKind::kCubby;
  double resolution_m = 0;         // OctoMap leaf size chosen from the ladder
  std::uint32_t octree_nodes = 0;  // cells with children (the artifact's node count)
  std::uint32_t occupied_leaves = 0;
  Eigen::Vector3d offset_m = Eigen::Vector3d::Zero();  // robot frame = octree frame + offset
  double azimuth_lo_rad = 0, azimuth_hi_rad = 0;       // the scene's extent seen from the base
  BoxTree tree;                                        // OctoMap's occupied leaves, one box per node, octree frame
};

// Voxelizes `boxes` (robot frame) at `resolution_m`: a voxel is occupied
// when its cube overlaps a box. Returns the octree, its cell count and
// offset. Throws std::invalid_argument for an empty scene or resolution <= 0.
SceneOctree VoxelizeScene(const std::vector<Aabbd>& boxes, double resolution_m);

// The scene at the ladder's resolution (see above). Throws std::runtime_error
// if no step lands in [kMinOctreeNodes, kMaxOctreeNodes].
SceneOctree BuildSceneOctree(MpinetSceneKind kind, std::uint64_t seed);

// Each pose (its links, base to tip) turned so that its tip points at
// `yaws` azimuths across the scene and jittered (see above), shifted into
// the octree's frame. yaws >= 1; every pose non-empty.
std::vector<Obbd> JitteredArmQueries(const std::vector<std::vector<Obbd>>& poses, int yaws, const SceneOctree& scene,
                                     std::uint64_t seed);

}  // namespace rc
