#include "robocore/ball_query/ball_query_tree.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>

namespace rc {

BallQueryTree::BallQueryTree(std::size_t dimension) : dimension_(dimension) {
  if (dimension == 0) throw std::invalid_argument("BallQueryTree: dimension must be at least 1");
}

int BallQueryTree::Allocate() {
  if (!free_nodes_.empty()) {
    const int node = free_nodes_.back();
    free_nodes_.pop_back();
    nodes_[node] = Node{};
    return node;
  }
  nodes_.emplace_back();
  boxes_.resize(boxes_.size() + 2 * dimension_);
  return static_cast<int>(nodes_.size() - 1);
}

void BallQueryTree::Release(int node) { free_nodes_.push_back(node); }

void BallQueryTree::SetLeafBox(int leaf) {
  const double* p = Coordinates(nodes_[leaf].state);
  double* lo = &boxes_[std::size_t(leaf) * 2 * dimension_];
  std::copy(p, p + dimension_, lo);
  std::copy(p, p + dimension_, lo + dimension_);
}

void BallQueryTree::UnionBox(int node) {
  const int a = nodes_[node].child[0], b = nodes_[node].child[1];
  double* lo = &boxes_[std::size_t(node) * 2 * dimension_];
  double* hi = lo + dimension_;
  for (std::size_t i = 0; i < dimension_; ++i) {
    lo[i] = std::min(Lo(a)[i], Lo(b)[i]);
    hi[i] = std::max(Hi(a)[i], Hi(b)[i]);
  }
}

void BallQueryTree::RefitUpwards(int node) {
  for (; node >= 0; node = nodes_[node].parent) UnionBox(node);
}

double BallQueryTree::Extent(int node) const {
  double e = 0;
  for (std::size_t i = 0; i < dimension_; ++i) e += Hi(node)[i] - Lo(node)[i];
  return e;
}

double BallQueryTree::UnionExtent(int node, int leaf) const {
  double e = 0;
  for (std::size_t i = 0; i < dimension_; ++i)
    e += std::max(Hi(node)[i], Hi(leaf)[i]) - std::min(Lo(node)[i], Lo(leaf)[i]);
  return e;
}

// Box2D's sibling choice with the summed extents as the cost (a point set
// in n-D has no useful volume): descend while a child is cheaper than
// pairing the leaf with the current node.
void BallQueryTree::InsertLeaf(int leaf) {
  if (root_ < 0) {
    root_ = leaf;
    nodes_[leaf].parent = -1;
    return;
  }
  int sibling = root_;
  while (!IsLeaf(sibling)) {
    const double extent = Extent(sibling);
    const double combined = UnionExtent(sibling, leaf);
    const double here = 2 * combined;
    const double inherited = 2 * (combined - extent);
    double cost[2];
    for (int c = 0; c < 2; ++c) {
      const int child = nodes_[sibling].child[c];
      cost[c] = UnionExtent(child, leaf) + inherited - (IsLeaf(child) ? 0.0 : Extent(child));
    }
    if (here < cost[0] && here < cost[1]) break;
    sibling = nodes_[sibling].child[cost[1] < cost[0] ? 1 : 0];
  }
  const int old_parent = nodes_[sibling].parent;
  const int parent = Allocate();
  nodes_[parent].parent = old_parent;
  nodes_[parent].child[0] = sibling;
  nodes_[parent].child[1] = leaf;
  nodes_[sibling].parent = parent;
  nodes_[leaf].parent = parent;
  if (old_parent < 0) {
    root_ = parent;
  } else {
    Node& op = nodes_[old_parent];
    op.child[op.child[0] == sibling ? 0 : 1] = parent;
  }
  RefitUpwards(parent);
}

void BallQueryTree::RemoveLeaf(int leaf) {
  if (leaf == root_) {
    root_ = -1;
    return;
  }
  const int parent = nodes_[leaf].parent;
  const int sibling = nodes_[parent].child[nodes_[parent].child[0] == leaf ? 1 : 0];
  const int grand = nodes_[parent].parent;
  nodes_[sibling].parent = grand;
  if (grand < 0) {
    root_ = sibling;
  } else {
    Node& g = nodes_[grand];
    g.child[g.child[0] == parent ? 0 : 1] = sibling;
    RefitUpwards(grand);
  }
  Release(parent);
}

BallStateId BallQueryTree::Insert(const double* coordinates) {
  for (std::size_t i = 0; i < dimension_; ++i)
    if (!std::isfinite(coordinates[i]))
      throw std::invalid_argument("BallQueryTree::Insert: coordinate " + std::to_string(i) + " is " +
                                  std::to_string(coordinates[i]) + " (must be finite)");
  BallStateId id;
  if (!free_ids_.empty()) {
    id = free_ids_.back();
    free_ids_.pop_back();
  } else {
    id = static_cast<BallStateId>(live_.size());
    if (id >= (BallStateId{1} << 31)) throw std::length_error("BallQueryTree: more than 2^31 states");
    live_.push_back(false);
    sequence_.push_back(0);
    leaf_of_.push_back(-1);
    coordinates_.resize(coordinates_.size() + dimension_);
  }
  std::copy(coordinates, coordinates + dimension_, coordinates_.begin() + std::size_t{id} * dimension_);
  live_[id] = true;
  sequence_[id] = next_sequence_++;
  ++live_count_;
  const int leaf = Allocate();
  nodes_[leaf].state = id;
  leaf_of_[id] = leaf;
  SetLeafBox(leaf);
  InsertLeaf(leaf);
  if (live_count_ >= 8 && live_count_ >= 2 * built_size_) Rebuild();
  return id;
}

void BallQueryTree::Remove(BallStateId id) {
  if (!IsLive(id))
    throw std::invalid_argument("BallQueryTree::Remove: state " + std::to_string(id) + " is not in the tree");
  const int leaf = leaf_of_[id];
  RemoveLeaf(leaf);
  Release(leaf);
  live_[id] = false;
  leaf_of_[id] = -1;
  --live_count_;
  free_ids_.insert(std::upper_bound(free_ids_.begin(), free_ids_.end(), id, std::greater<>()), id);
  ++removed_since_build_;
  if (live_count_ == 0) {
    Clear();
  } else if (2 * removed_since_build_ > built_size_) {
    Rebuild();
  }
}

void BallQueryTree::Clear() {
  coordinates_.clear();
  sequence_.clear();
  leaf_of_.clear();
  live_.clear();
  free_ids_.clear();
  live_count_ = 0;
  nodes_.clear();
  boxes_.clear();
  free_nodes_.clear();
  root_ = -1;
  built_size_ = 0;
  removed_since_build_ = 0;
  // next_sequence_ keeps counting: sequences stay unique over the tree's life.
}

void BallQueryTree::Rebuild() {
  std::vector<BallStateId> ids;
  ids.reserve(live_count_);
  for (BallStateId id = 0; id < live_.size(); ++id)
    if (live_[id]) ids.push_back(id);
  nodes_.clear();
  boxes_.clear();
  free_nodes_.clear();
  nodes_.reserve(2 * ids.size());
  boxes_.reserve(4 * ids.size() * dimension_);
  root_ = ids.empty() ? -1 : Build(ids, 0, ids.size(), -1);
  built_size_ = live_count_;
  removed_since_build_ = 0;
  ++rebuilds_;
}

// Top-down, median split on the widest axis; nodes are allocated in
// preorder so a parent and its near subtree sit close in the device array.
int BallQueryTree::Build(std::vector<BallStateId>& ids, std::size_t begin, std::size_t end, int parent) {
  const int node = Allocate();
  nodes_[node].parent = parent;
  if (end - begin == 1) {
    nodes_[node].state = ids[begin];
    leaf_of_[ids[begin]] = node;
    SetLeafBox(node);
    return node;
  }
  std::size_t axis = 0;
  double widest = -1;
  for (std::size_t i = 0; i < dimension_; ++i) {
    double lo = Coordinates(ids[begin])[i], hi = lo;
    for (std::size_t k = begin + 1; k < end; ++k) {
      lo = std::min(lo, Coordinates(ids[k])[i]);
      hi = std::max(hi, Coordinates(ids[k])[i]);
    }
    if (hi - lo > widest) {
      widest = hi - lo;
      axis = i;
    }
  }
  const std::size_t mid = begin + (end - begin) / 2;
  // Ties on the axis are broken by id, so the build is deterministic.
  std::nth_element(ids.begin() + begin, ids.begin() + mid, ids.begin() + end, [&](BallStateId a, BallStateId b) {
    const double ca = Coordinates(a)[axis], cb = Coordinates(b)[axis];
    return ca < cb || (ca == cb && a < b);
  });
  const int a = Build(ids, begin, mid, node);
  const int b = Build(ids, mid, end, node);
  nodes_[node].child[0] = a;
  nodes_[node].child[1] = b;
  UnionBox(node);
  return node;
}

int BallQueryTree::Depth() const {
  if (root_ < 0) return 0;
  int deepest = 0;
  std::vector<std::pair<int, int>> stack{{root_, 0}};
  while (!stack.empty()) {
    const auto [node, depth] = stack.back();
    stack.pop_back();
    deepest = std::max(deepest, depth);
    if (!IsLeaf(node))
      for (int c = 0; c < 2; ++c) stack.push_back({nodes_[node].child[c], depth + 1});
  }
  return deepest;
}

}  // namespace rc
