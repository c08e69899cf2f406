#pragma once
// A dynamic bounding-volume hierarchy (BVH2) over states in R^n: the tree
// the ball-query kernel traverses (ball_query_search.h).
//
// Host structure: a binary tree of axis-aligned boxes in double precision;
// every leaf is one state (as RTNN puts one primitive per point), its box
// the state itself (lo = hi). States are added one at a time, as RRT* does:
// a new leaf goes next to the sibling that grows the boxes' summed extents
// least (the dynamic-AABB-tree insertion of Box2D's b2DynamicTree, without
// rotations), and the whole tree is rebuilt top-down (median split on the
// widest axis) whenever the state count doubles since the last build, or
// half of the built states were removed. The rebuild keeps the depth near
// log2(size); its cost, O(size log size) per doubling, is amortized O(log
// size) per add.
//
// Device node layout (what the backends fetch, one node per loop pass of
// the ball-query programs). An internal node holds both children's boxes,
// so one fetch tests both; a child that is a state is inlined as its
// coordinates, so states need no fetch of their own:
//   offset 0          child a: lo[n] doubles (a state: its coordinates)
//   offset 8n         child a: hi[n] doubles (a state: its coordinates again)
//   offset 16n        child b: lo[n], then hi[n] at 24n
//   offset 32n        child a reference: uint32 (internal node index, or the
//                     state id with the top bit set)
//   offset 32n + 4    child b reference: uint32
//   total             32n + 8 bytes: 168 bytes (6 sectors of 32 bytes) for
//                     the 5-D arm.
// Doubles, not floats, because a state's coordinates must give exactly the
// distance OMPL's RealVectorStateSpace computes (the answers must equal
// brute force bit for bit). The device array is indexed like the host node
// pool: node i sits at base + i * (32n + 8); pool slots that hold leaves are
// never fetched. A tree of one state is one fetch holding the
// state as child a and an empty child b (at the root leaf's slot).
#include <cstddef>
#include <cstdint>
#include <vector>

namespace rc {

using BallStateId = std::uint32_t;

class BallQueryTree {
 public:
  // Throws std::invalid_argument if dimension is 0.
  explicit BallQueryTree(std::size_t dimension);

  std::size_t dimension() const { return dimension_; }
  std::size_t size() const { return live_count_; }
  bool empty() const { return live_count_ == 0; }

  // Copies the state's coordinates and returns its id (the ids of removed
  // states are reused, lowest first). Throws std::invalid_argument for a
  // coordinate that is not finite.
  BallStateId Insert(const double* coordinates);
  // Throws std::invalid_argument if id is not a live state.
  void Remove(BallStateId id);
  void Clear();

  bool IsLive(BallStateId id) const { return id < live_.size() && live_[id]; }
  const double* Coordinates(BallStateId id) const { return &coordinates_[std::size_t{id} * dimension_]; }
  // Insertion order (strictly increasing over the tree's life): the
  // tie-break between states at equal distance.
  std::uint64_t Sequence(BallStateId id) const { return sequence_[id]; }

  // Traversal view of the host tree. root() is -1 when empty.
  int root() const { return root_; }
  bool IsLeaf(int node) const { return nodes_[node].child[0] < 0; }
  int Child(int node, int which) const { return nodes_[node].child[which]; }
  BallStateId StateOf(int leaf) const { return nodes_[leaf].state; }
  const double* Lo(int node) const { return &boxes_[std::size_t(node) * 2 * dimension_]; }
  const double* Hi(int node) const { return Lo(node) + dimension_; }

  // Device layout.
  static std::uint32_t NodeBytes(std::size_t dimension) { return static_cast<std::uint32_t>(32 * dimension + 8); }
  std::uint32_t node_bytes() const { return NodeBytes(dimension_); }
  std::size_t node_slots() const { return nodes_.size(); }  // device array length

  std::size_t rebuilds() const { return rebuilds_; }
  int Depth() const;  // longest root-to-leaf path in edges (tests, docs)

 private:
  struct Node {
    int parent = -1;
    int child[2] = {-1, -1};  // both -1 for a leaf
    BallStateId state = 0;    // leaves only
  };

  int Allocate();
  void Release(int node);
  void SetLeafBox(int leaf);
  void UnionBox(int node);  // box of an internal node from its children
  void RefitUpwards(int node);
  void InsertLeaf(int leaf);
  void RemoveLeaf(int leaf);
  void Rebuild();
  int Build(std::vector<BallStateId>& ids, std::size_t begin, std::size_t end, int parent);
  double Extent(int node) const;                 // summed box extents
  double UnionExtent(int node, int leaf) const;  // summed extents of the union

  std::size_t dimension_;
  // States, by id.
  std::vector<double> coordinates_;
  std::vector<std::uint64_t> sequence_;
  std::vector<int> leaf_of_;
  std::vector<bool> live_;
  std::vector<BallStateId> free_ids_;  // kept sorted descending: back() is the lowest
  std::size_t live_count_ = 0;
  std::uint64_t next_sequence_ = 0;
  // Tree.
  std::vector<Node> nodes_;
  std::vector<double> boxes_;  // 2n per node: lo then hi
  std::vector<int> free_nodes_;
  int root_ = -1;
  std::size_t built_size_ = 0;
  std::size_t removed_since_build_ = 0;
  std::size_t rebuilds_ = 0;
};

}  // namespace rc
