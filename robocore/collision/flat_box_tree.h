#pragma once
// The node array a backend fetches: a BoxTree flattened into fixed-size
// nodes, one box per node, breadth-first, children contiguous.
//
// Node layout (bytes):
//   Scalar centre[3], half[3]   the node's box (a leaf: its scene box)
//   uint32 first_child          internal: index of the first child;
//                               leaf: index of its box in the scene list
//   uint16 child_count          0 for a leaf
//   uint16 depth                root = 0
//   float:  12 + 12 + 8 = 32 bytes, one 32-byte L1 sector;
//   double: 24 + 24 + 8 = 56, padded to 64 (alignas(32)) so a node is
//           always exactly two sectors and never straddles a third.
// The artifact's octree node is 432 bytes (REFERENCE.md section 2): a child
// address, 8 child status codes and 8 child boxes as double centre + half
// extent, plus the level. One fetch there feeds 8 box tests (54 bytes per
// test, empty children included); here one 32-byte (float) or 64-byte
// (double) fetch feeds one test, empty children are never stored, and a
// query fetches only the children of nodes it could not reject.
//
// Leaves hold their scene box exactly (cast to Scalar). Internal boxes are
// conservative: they contain the Scalar-rounded boxes below them, rounded
// outward, plus a margin of 256 ulps of the scene's half extent (root
// bounds; 0.15 mm in float for a 10 m scene). The SACT's rounding near
// contact is a few ulps of the radii and centre offset it handles, so a
// node whose box contains a leaf that overlaps the query is not rejected:
// the tree answers exactly what testing every box would (tests/collision
// check this, near contact and far from the origin; internal boxes shrunk
// by 1e-6 fail them, while the margin itself has not yet been needed:
// the SACT's rounding has been monotone in practice), at the price of a
// few extra visits within the margin. The guarantee assumes OBBs no larger than
// about 16 x the scene's half extent; a larger OBB can only differ within
// its own rounding (u x its size) of exact contact, where the box-by-box
// answer is itself decided by rounding.
#include <cstdint>
#include <vector>

#include "robocore/collision/aabb.h"
#include "robocore/collision/box_tree.h"

namespace rc {

template <typename Scalar>
struct alignas(32) FlatNode {
  Scalar centre[3];
  Scalar half[3];
  std::uint32_t first_child;
  std::uint16_t child_count;
  std::uint16_t depth;
  bool is_leaf() const { return child_count == 0; }
  Aabb<Scalar> box() const {
    Aabb<Scalar> b;
    for (int j = 0; j < 3; ++j) b.centre[j] = centre[j], b.half[j] = half[j];
    return b;
  }
};
static_assert(sizeof(FlatNode<float>) == 32, "float node: one 32-byte sector");
static_assert(sizeof(FlatNode<double>) == 64, "double node: two 32-byte sectors");

template <typename Scalar>
class FlatBoxTree {
 public:
  FlatBoxTree() = default;
  // Throws std::invalid_argument if a node has more than 65535 children or
  // the tree is deeper than 65535 (neither happens with the three builders).
  explicit FlatBoxTree(const BoxTree& tree);

  const std::vector<FlatNode<Scalar>>& nodes() const { return nodes_; }
  // The scene's boxes in Scalar, as the leaves hold them (for brute force).
  const std::vector<Aabb<Scalar>>& boxes() const { return boxes_; }
  BoxTreeKind kind() const { return kind_; }
  std::uint32_t max_children() const { return max_children_; }
  static constexpr std::uint32_t node_bytes() { return sizeof(FlatNode<Scalar>); }
  std::uint64_t bytes() const { return nodes_.size() * std::uint64_t{node_bytes()}; }
  Scalar internal_margin() const { return internal_margin_; }  // m

 private:
  std::vector<FlatNode<Scalar>> nodes_;
  std::vector<Aabb<Scalar>> boxes_;
  BoxTreeKind kind_ = BoxTreeKind::kMedianSplit;
  std::uint32_t max_children_ = 2;
  Scalar internal_margin_ = 0;
};

extern template class FlatBoxTree<float>;
extern template class FlatBoxTree<double>;

}  // namespace rc
