#pragma once
// A scene as a tree of axis-aligned boxes, before flattening (see
// flat_box_tree.h for the array the backends fetch).
//
// The scene is the union of `boxes`. Every leaf holds exactly one box, so a
// query tests one box per node it visits (one SACT per node fetch, the
// contract of programs/sact_obb_aabb.asm). An internal node's bounds
// contain every box below it, so a query that misses a node misses its
// whole subtree. Nodes are stored breadth-first with each node's children
// contiguous (root at 0), the layout a fetch unit walks.
//
// Three builders, one per kind of scene (a planar scene never builds a 3D
// tree; DESIGN.md "model only what a scene needs"):
//   BuildMedianSplitTree   any list of boxes (this file)
//   BuildQuadtreeFromGrid  2D occupancy grid, occupied cells (quadtree_from_grid.h)
//   BuildOctreeFromOctoMap OctoMap occupied leaves (octree_from_octomap.h)
// An internal node with a single child is dropped (its child takes its
// place): its bounds would equal the child's, so it would cost a fetch and
// prune nothing.
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "robocore/collision/aabb.h"

namespace rc {

enum class BoxTreeKind : std::uint8_t { kMedianSplit, kQuadtree, kOctree };
const char* ToString(BoxTreeKind kind);

inline constexpr std::uint32_t kNoBox = std::numeric_limits<std::uint32_t>::max();

struct BoxTreeNode {
  Eigen::Vector3d lower = Eigen::Vector3d::Zero();  // m; contains every box below
  Eigen::Vector3d upper = Eigen::Vector3d::Zero();  // m
  std::uint32_t first_child = 0;                    // index in BoxTree::nodes; children are contiguous
  std::uint32_t child_count = 0;                    // 0 for a leaf
  std::uint32_t box = kNoBox;                       // leaf: index in BoxTree::boxes
  std::uint32_t depth = 0;                          // root = 0
  bool is_leaf() const { return child_count == 0; }
};

struct BoxTree {
  BoxTreeKind kind = BoxTreeKind::kMedianSplit;
  std::vector<Aabbd> boxes;        // the scene: the union of these boxes
  std::vector<BoxTreeNode> nodes;  // breadth-first; empty for an empty scene
  std::uint32_t max_children = 2;  // 2 / 4 / 8
  std::uint32_t height() const;    // levels (0 for an empty tree)
};

// Binary tree over a list of boxes: split at the median box centre along
// the axis where the centres spread most (Ericson, Real-Time Collision
// Detection, 6.2.1, "median of the centroid coordinates"). Balanced, so
// height ceil(log2 n) + 1; O(n log n) time, 2n - 1 nodes. Not SAH: SAH
// minimises the expected cost of rays, whose cost is in the leaves they
// pass through; a bounded OBB query mostly pays for the internal nodes it
// cannot reject, and a balanced tree bounds that path.
// Throws std::invalid_argument for a box with a negative or non-finite
// half extent or a non-finite centre.
BoxTree BuildMedianSplitTree(std::vector<Aabbd> boxes);

// --- For builders ---------------------------------------------------------
// A tree under construction: children as indices into the same pool.
struct BuildNode {
  std::vector<std::uint32_t> children;  // pool indices
  std::uint32_t box = kNoBox;           // leaves only
};
// Lays out the pool breadth-first from `root`, computes every node's bounds
// (leaf bounds rounded one ulp outward, so they contain the box exactly),
// and drops single-child internal nodes.
BoxTree LayOutBreadthFirst(BoxTreeKind kind, std::uint32_t max_children, std::vector<Aabbd> boxes,
                           const std::vector<BuildNode>& pool, std::uint32_t root);
// Throws std::invalid_argument naming the box if it is not a valid box.
void CheckBox(const Aabbd& box, std::size_t index);

}  // namespace rc
