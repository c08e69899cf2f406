#include "backends/calibration/mpinet_like_scenes.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <Eigen/Geometry>
#include <octomap/OcTree.h>

#include "common/random_stream.h"
#include "robocore/collision/octree_from_octomap.h"
#include "robocore/collision/shelf_scene.h"

namespace rc {
namespace {

Aabbd FromCorners(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  return Aabbd{0.5 * (lo + hi), 0.5 * (hi - lo)};
}

void Append(std::vector<Aabbd>& to, const std::vector<Aabbd>& more, const Eigen::Vector3d& shift) {
  for (Aabbd b : more) {
    b.centre += shift;
    to.push_back(b);
  }
}

// A bookcase of cubbies facing the robot.
std::vector<Aabbd> Cubby(std::uint64_t seed) {
  ShelfSceneOptions o;
  o.front_x_m = 0.5;
  o.depth_m = 0.4;
  o.width_m = 1.4;
  o.height_m = 0.9;
  o.rows = 3;
  o.columns = 4;
  o.objects_per_cubby = 1;
  o.mirrored_behind = false;
  o.seed = seed;
  return MakeShelfScene(o);
}

// A cubby whose upper cells are merged: four cells below, two wide ones
// above, one bookcase standing on the other.
std::vector<Aabbd> MergedCubby(std::uint64_t seed) {
  ShelfSceneOptions o;
  o.front_x_m = 0.5;
  o.depth_m = 0.4;
  o.width_m = 1.4;
  o.height_m = 0.45;
  o.rows = 1;
  o.columns = 4;
  o.objects_per_cubby = 1;
  o.mirrored_behind = false;
  o.seed = seed;
  std::vector<Aabbd> boxes = MakeShelfScene(o);
  o.columns = 2;
  o.objects_per_cubby = 2;
  o.seed = seed + 1;
  Append(boxes, MakeShelfScene(o), {0, 0, o.height_m});
  return boxes;
}

// A dresser against the far wall with its drawers pulled out by seeded
// amounts toward the robot: carcass panels, and per drawer a front, a
// bottom, two sides and a back.
std::vector<Aabbd> Dresser(std::uint64_t seed) {
  const double x0 = 0.6, x1 = 1.0, y0 = -0.5, y1 = 0.5, height = 0.9, t = 0.02;
  const int drawers = 4;
  std::vector<Aabbd> boxes = {
      FromCorners({x1 - t, y0, 0}, {x1, y1, height}),                                                       // back
      FromCorners({x0, y0, 0}, {x1, y0 + t, height}),                                                       // sides
      FromCorners({x0, y1 - t, 0}, {x1, y1, height}), FromCorners({x0, y0, height - t}, {x1, y1, height}),  // top
  };
  RandomStream rng(seed, StreamPurpose::kMapGeneration, 0, 0);
  const double slot = height / drawers;
  for (int k = 0; k < drawers; ++k) {
    const double z0 = k * slot, z1 = (k + 1) * slot - t;
    boxes.push_back(FromCorners({x0, y0, z0}, {x1 - t, y1, z0 + t}));  // rail under the drawer
    const double out = rng.Uniform(0.0, 0.3);                          // m pulled out
    const double f = x0 - out, b = x1 - t - out - 0.02;
    const double dy0 = y0 + t + 0.01, dy1 = y1 - t - 0.01, dz0 = z0 + t + 0.005;
    boxes.push_back(FromCorners({f - t, y0 + t, z0 + t}, {f, y1 - t, z1}));  // front
    boxes.push_back(FromCorners({f, dy0, dz0}, {b, dy1, dz0 + t}));          // bottom
    boxes.push_back(FromCorners({f, dy0, dz0}, {b, dy0 + t, z1 - 0.04}));    // sides
    boxes.push_back(FromCorners({f, dy1 - t, dz0}, {b, dy1, z1 - 0.04}));
    boxes.push_back(FromCorners({b - t, dy0, dz0}, {b, dy1, z1 - 0.04}));  // back
  }
  return boxes;
}

// A table with seeded objects resting on it.
std::vector<Aabbd> Tabletop(std::uint64_t seed) {
  const double x0 = 0.35, x1 = 1.15, y0 = -0.6, y1 = 0.6, top = 0.43, t = 0.03, leg = 0.04;
  std::vector<Aabbd> boxes = {FromCorners({x0, y0, top - t}, {x1, y1, top})};
  for (double x : {x0, x1 - leg})
    for (double y : {y0, y1 - leg}) boxes.push_back(FromCorners({x, y, 0}, {x + leg, y + leg, top - t}));
  RandomStream rng(seed, StreamPurpose::kMapGeneration, 1, 0);
  for (int k = 0; k < 10; ++k) {
    // One draw per declarator (declarators are sequenced, a call's
    // arguments are not): z, y, x is the order GCC gave the scenes so far.
    const double half_z = rng.Uniform(0.03, 0.12), half_y = rng.Uniform(0.02, 0.08), half_x = rng.Uniform(0.02, 0.08);
    const Eigen::Vector3d half(half_x, half_y, half_z);
    const double cx = rng.Uniform(x0 + half.x(), x1 - half.x()), cy = rng.Uniform(y0 + half.y(), y1 - half.y());
    boxes.push_back(Aabbd{{cx, cy, top + half.z()}, half});
  }
  return boxes;
}

// Cells with children below (and including) the smallest cell holding
// every leaf: descend from the root while a node has exactly one child.
std::uint32_t CountOctreeNodes(const octomap::OcTree& tree) {
  const octomap::OcTreeNode* node = tree.getRoot();
  if (!node) return 0;
  auto children_of = [&](const octomap::OcTreeNode* n) {
    int count = 0;
    for (unsigned i = 0; i < 8; ++i) count += tree.nodeChildExists(n, i);
    return count;
  };
  while (children_of(node) == 1)
    for (unsigned i = 0; i < 8; ++i)
      if (tree.nodeChildExists(node, i)) {
        node = tree.getNodeChild(node, i);
        break;
      }
  std::uint32_t cells = 0;
  std::vector<const octomap::OcTreeNode*> stack = {node};
  while (!stack.empty()) {
    const octomap::OcTreeNode* n = stack.back();
    stack.pop_back();
    if (!tree.nodeHasChildren(n)) continue;
    ++cells;
    for (unsigned i = 0; i < 8; ++i)
      if (tree.nodeChildExists(n, i)) stack.push_back(tree.getNodeChild(n, i));
  }
  return cells;
}

}  // namespace

const char* ToString(MpinetSceneKind kind) {
  switch (kind) {
    case MpinetSceneKind::kCubby: return "cubby";
    case MpinetSceneKind::kMergedCubby: return "merged cubby";
    case MpinetSceneKind::kDresser: return "dresser";
    case MpinetSceneKind::kTabletop: return "tabletop";
  }
  return "?";
}

std::vector<Aabbd> MakeMpinetLikeScene(MpinetSceneKind kind, std::uint64_t seed) {
  switch (kind) {
    case MpinetSceneKind::kCubby: return Cubby(seed);
    case MpinetSceneKind::kMergedCubby: return MergedCubby(seed);
    case MpinetSceneKind::kDresser: return Dresser(seed);
    case MpinetSceneKind::kTabletop: return Tabletop(seed);
  }
  throw std::logic_error("unhandled scene kind");
}

SceneOctree VoxelizeScene(const std::vector<Aabbd>& boxes, double resolution_m) {
  if (boxes.empty()) throw std::invalid_argument("voxelize: the scene has no box");
  if (!(resolution_m > 0)) throw std::invalid_argument("voxelize: resolution must be > 0 m");
  SceneOctree out;
  out.resolution_m = resolution_m;
  out.offset_m = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  out.azimuth_lo_rad = std::numeric_limits<double>::infinity();
  out.azimuth_hi_rad = -out.azimuth_lo_rad;
  for (const Aabbd& b : boxes) {
    out.offset_m = out.offset_m.cwiseMin(b.centre - b.half);
    for (int corner = 0; corner < 4; ++corner) {
      const double x = b.centre.x() + (corner & 1 ? b.half.x() : -b.half.x());
      const double y = b.centre.y() + (corner & 2 ? b.half.y() : -b.half.y());
      out.azimuth_lo_rad = std::min(out.azimuth_lo_rad, std::atan2(y, x));
      out.azimuth_hi_rad = std::max(out.azimuth_hi_rad, std::atan2(y, x));
    }
  }
  octomap::OcTree tree(resolution_m);
  for (const Aabbd& b : boxes) {
    const Eigen::Vector3d lo = b.centre - b.half - out.offset_m, hi = b.centre + b.half - out.offset_m;
    // Keys of the voxels whose cube meets [lo, hi]; a face on a voxel
    // boundary touches the voxel beyond it, which does not overlap.
    octomap::OcTreeKey klo, khi;
    if (!tree.coordToKeyChecked(lo.x(), lo.y(), lo.z(), klo) || !tree.coordToKeyChecked(hi.x(), hi.y(), hi.z(), khi))
      throw std::invalid_argument("voxelize: the scene is too large for OctoMap's key range");
    for (unsigned x = klo[0]; x <= khi[0]; ++x)
      for (unsigned y = klo[1]; y <= khi[1]; ++y)
        for (unsigned z = klo[2]; z <= khi[2]; ++z)
          tree.updateNode(octomap::OcTreeKey(static_cast<octomap::key_type>(x), static_cast<octomap::key_type>(y),
                                             static_cast<octomap::key_type>(z)),
                          true, /*lazy_eval=*/true);
  }
  tree.updateInnerOccupancy();
  tree.prune();
  out.octree_nodes = CountOctreeNodes(tree);
  out.tree = BuildOctreeFromOctoMap(tree);
  out.occupied_leaves = static_cast<std::uint32_t>(out.tree.boxes.size());
  return out;
}

SceneOctree BuildSceneOctree(MpinetSceneKind kind, std::uint64_t seed) {
  const std::vector<Aabbd> boxes = MakeMpinetLikeScene(kind, seed);
  std::string tried;
  for (int k = 0; k <= kResolutionSteps; ++k) {
    SceneOctree octree = VoxelizeScene(boxes, kCoarsestResolution * std::pow(2.0, -k / 4.0));
    octree.kind = kind;
    if (octree.octree_nodes >= kMinOctreeNodes) {
      if (octree.octree_nodes <= kMaxOctreeNodes) return octree;
      tried += " " + std::to_string(octree.octree_nodes);
      break;
    }
    tried += " " + std::to_string(octree.octree_nodes);
  }
  throw std::runtime_error(std::string("scene '") + ToString(kind) + "': no ladder resolution gives " +
                           std::to_string(kMinOctreeNodes) + "-" + std::to_string(kMaxOctreeNodes) +
                           " octree nodes (counts, coarse to fine:" + tried + ")");
}

std::vector<Obbd> JitteredArmQueries(const std::vector<std::vector<Obbd>>& poses, int yaws, const SceneOctree& scene,
                                     std::uint64_t seed) {
  if (yaws < 1) throw std::invalid_argument("arm queries: yaws must be >= 1");
  constexpr double kTranslationJitter = 0.02;  // m, per axis, uniform
  constexpr double kRotationJitter = 0.05;     // rad about a random axis, uniform
  RandomStream rng(seed, StreamPurpose::kTest, 2, 0);
  std::vector<Obbd> queries;
  for (int k = 0; k < yaws; ++k) {
    const double aim = scene.azimuth_lo_rad + (scene.azimuth_hi_rad - scene.azimuth_lo_rad) * (k + 0.5) / yaws;
    for (const std::vector<Obbd>& pose : poses) {
      if (pose.empty()) throw std::invalid_argument("arm queries: a pose without links");
      const Eigen::Vector3d& tip = pose.back().centre;
      const double turn = aim - std::atan2(tip.y(), tip.x());
      const Eigen::Matrix3d yaw = Eigen::AngleAxisd(turn, Eigen::Vector3d::UnitZ()).toRotationMatrix();
      for (const Obbd& link : pose) {
        const double axis_z = rng.Gaussian(), axis_y = rng.Gaussian(), axis_x = rng.Gaussian();  // as above
        Eigen::Vector3d axis(axis_x, axis_y, axis_z);
        axis = axis.norm() > 0 ? axis.normalized() : Eigen::Vector3d::UnitX();
        const Eigen::Matrix3d tilt =
            Eigen::AngleAxisd(rng.Uniform(-kRotationJitter, kRotationJitter), axis).toRotationMatrix();
        Obbd q = link;
        q.centre = yaw * link.centre - scene.offset_m;
        for (int j = 0; j < 3; ++j) q.centre[j] += rng.Uniform(-kTranslationJitter, kTranslationJitter);
        q.axes = tilt * yaw * link.axes;
        queries.push_back(q);
      }
    }
  }
  return queries;
}

}  // namespace rc
