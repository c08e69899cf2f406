#pragma once
// The flattened box tree (robocore/collision/flat_box_tree.h) and its
// depth-first traversal (box_tree_traversal.h), shared by the SACT and the
// sphere kernels: pop a node, fetch it, test its box, stop at the first
// leaf whose box the query overlaps, else push the children of an
// overlapping node in reverse order (the first child is visited first).
#include "backends/cuda/device_common.cuh"

namespace rc_cuda {

// FlatNode<Scalar>: 32 bytes in float, 64 in double (alignas(32)).
template <typename T>
struct alignas(32) FlatNode {
  T centre[3];                 // m
  T half[3];                   // m
  unsigned first_child;        // internal: first child; leaf: scene box index
  unsigned short child_count;  // 0 for a leaf
  unsigned short depth;
};

// TraversalOutcome, plus a stack-overflow flag (the host's stack grows; a
// thread's stack here is fixed, and a query that would overflow it stops
// and says so instead of answering wrongly).
struct TreeResult {
  unsigned colliding_box;  // kNoBox (0xffffffff) when free
  unsigned nodes_visited;
  unsigned char collides;
  unsigned char stack_overflow;
};

inline constexpr int kTreeStackEntries = 256;  // depth x children bound: 8-ary trees of depth 31

// Depth-first traversal with the node test `overlaps(node) -> bool`.
template <typename T, typename Test>
__device__ __forceinline__ TreeResult TraverseTree(const FlatNode<T>* __restrict__ nodes, int node_count,
                                                   Test&& overlaps) {
  TreeResult out{0xffffffffu, 0u, 0, 0};
  if (node_count == 0) return out;
  unsigned stack[kTreeStackEntries];
  int top = 0;
  stack[top++] = 0;
#pragma unroll 1
  while (top > 0) {
    const unsigned index = stack[--top];
    const FlatNode<T> node = nodes[index];  // RC_NODE_FETCH
    ++out.nodes_visited;
    if (!overlaps(node)) continue;
    if (node.child_count == 0) {
      out.collides = 1;
      out.colliding_box = node.first_child;
      return out;
    }
    if (top + node.child_count > kTreeStackEntries) {
      out.stack_overflow = 1;
      return out;
    }
#pragma unroll 1
    for (unsigned c = node.first_child + node.child_count; c-- > node.first_child;) stack[top++] = c;
  }
  return out;
}

}  // namespace rc_cuda
