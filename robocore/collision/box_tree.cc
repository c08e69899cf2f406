#include "robocore/collision/box_tree.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace rc {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Follows single-child chains down to the node that actually branches.
std::uint32_t SkipSingleChildren(const std::vector<BuildNode>& pool, std::uint32_t n) {
  while (pool[n].children.size() == 1) n = pool[n].children.front();
  return n;
}

std::uint32_t BuildMedian(std::vector<BuildNode>& pool, const std::vector<Aabbd>& boxes,
                          std::vector<std::uint32_t>& order, std::size_t lo, std::size_t hi) {
  const auto self = static_cast<std::uint32_t>(pool.size());
  pool.emplace_back();
  if (hi - lo == 1) {
    pool[self].box = order[lo];
    return self;
  }
  Eigen::Vector3d min_c = Eigen::Vector3d::Constant(kInf), max_c = -min_c;
  for (std::size_t i = lo; i < hi; ++i) {
    min_c = min_c.cwiseMin(boxes[order[i]].centre);
    max_c = max_c.cwiseMax(boxes[order[i]].centre);
  }
  int axis = 0;
  (max_c - min_c).maxCoeff(&axis);
  const std::size_t mid = lo + (hi - lo) / 2;
  // Ties broken by box index, so the tree does not depend on the sort.
  std::nth_element(order.begin() + lo, order.begin() + mid, order.begin() + hi, [&](std::uint32_t a, std::uint32_t b) {
    const double ca = boxes[a].centre[axis], cb = boxes[b].centre[axis];
    return ca < cb || (ca == cb && a < b);
  });
  const std::uint32_t left = BuildMedian(pool, boxes, order, lo, mid);
  const std::uint32_t right = BuildMedian(pool, boxes, order, mid, hi);
  pool[self].children = {left, right};
  return self;
}

}  // namespace

const char* ToString(BoxTreeKind kind) {
  switch (kind) {
    case BoxTreeKind::kMedianSplit: return "median-split binary tree";
    case BoxTreeKind::kQuadtree: return "quadtree";
    case BoxTreeKind::kOctree: return "octree";
  }
  return "?";
}

std::uint32_t BoxTree::height() const {
  std::uint32_t h = 0;
  for (const BoxTreeNode& n : nodes) h = std::max(h, n.depth + 1);
  return h;
}

void CheckBox(const Aabbd& box, std::size_t index) {
  if (!box.centre.allFinite() || !box.half.allFinite() || (box.half.array() < 0).any())
    throw std::invalid_argument("box " + std::to_string(index) +
                                ": centre and half extents must be finite, half extents >= 0");
}

BoxTree LayOutBreadthFirst(BoxTreeKind kind, std::uint32_t max_children, std::vector<Aabbd> boxes,
                           const std::vector<BuildNode>& pool, std::uint32_t root) {
  BoxTree tree;
  tree.kind = kind;
  tree.max_children = max_children;
  tree.boxes = std::move(boxes);
  if (pool.empty()) return tree;
  // Breadth-first: a node's children are appended together when it is
  // dequeued, so they are contiguous and come after it.
  std::vector<std::uint32_t> source{SkipSingleChildren(pool, root)};
  tree.nodes.emplace_back();
  for (std::size_t at = 0; at < source.size(); ++at) {
    const BuildNode& b = pool[source[at]];
    if (b.children.empty()) {
      tree.nodes[at].box = b.box;
      continue;
    }
    tree.nodes[at].first_child = static_cast<std::uint32_t>(tree.nodes.size());
    tree.nodes[at].child_count = static_cast<std::uint32_t>(b.children.size());
    const std::uint32_t depth = tree.nodes[at].depth + 1;
    for (std::uint32_t c : b.children) {
      source.push_back(SkipSingleChildren(pool, c));
      tree.nodes.emplace_back();
      tree.nodes.back().depth = depth;
    }
  }
  // Bounds bottom-up: children always follow their parent.
  for (std::size_t i = tree.nodes.size(); i-- > 0;) {
    BoxTreeNode& n = tree.nodes[i];
    if (n.is_leaf()) {
      const Aabbd& box = tree.boxes.at(n.box);
      for (int j = 0; j < 3; ++j) {
        n.lower[j] = std::nextafter(box.centre[j] - box.half[j], -kInf);
        n.upper[j] = std::nextafter(box.centre[j] + box.half[j], kInf);
      }
      continue;
    }
    n.lower = Eigen::Vector3d::Constant(kInf);
    n.upper = -n.lower;
    for (std::uint32_t c = n.first_child; c < n.first_child + n.child_count; ++c) {
      n.lower = n.lower.cwiseMin(tree.nodes[c].lower);
      n.upper = n.upper.cwiseMax(tree.nodes[c].upper);
    }
  }
  return tree;
}

BoxTree BuildMedianSplitTree(std::vector<Aabbd> boxes) {
  for (std::size_t i = 0; i < boxes.size(); ++i) CheckBox(boxes[i], i);
  std::vector<BuildNode> pool;
  if (boxes.empty()) return LayOutBreadthFirst(BoxTreeKind::kMedianSplit, 2, std::move(boxes), pool, 0);
  pool.reserve(2 * boxes.size());
  std::vector<std::uint32_t> order(boxes.size());
  std::iota(order.begin(), order.end(), 0u);
  const std::uint32_t root = BuildMedian(pool, boxes, order, 0, boxes.size());
  return LayOutBreadthFirst(BoxTreeKind::kMedianSplit, 2, std::move(boxes), pool, root);
}

}  // namespace rc
