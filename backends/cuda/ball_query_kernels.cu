// The ball query on the CUDA cores, one query per thread: BallNearestK of
// robocore/ball_query/ball_query_search.cc (k nearest states, radius grown
// until k are found, the radius shrunk to the k-th best distance on the
// way when early exit is on), over the device node layout of
// ball_query_tree.h, in both formulations:
//   P-Sphere (programs/ball_query_psphere.asm): a child is kept when the
//     query sphere touches its box (squared distance to the box), and the
//     nearer child is visited first;
//   P-Ray (programs/ball_query_pray.asm): a child is kept when the query
//     point lies in its box grown by the radius, in stored order.
// A child that is a state is tested by its Euclidean distance (a square
// root, as OMPL's RealVectorStateSpace, so the answers equal brute force)
// and offered to the sorted k-best list (ties by insertion sequence).
//
// Written for the 5-D arm (kDim = 5) and k <= kMaxK = 16; the radius-query
// form (BallWithinRadius, unbounded k) is not compiled.
//
// Entry points: rc_ball_query_{psphere,pray}_{fp32,fp64}.
#include "backends/cuda/device_common.cuh"

namespace rc_cuda {

inline constexpr int kDim = 5;
inline constexpr int kMaxK = 16;
inline constexpr int kBallStackEntries = 128;
inline constexpr unsigned kStateBit = 0x80000000u;  // a child reference naming a state

// One BVH2 node (ball_query_tree.h): both children's boxes, then their
// references (an internal node index, or a state id with the top bit set;
// a state's box is the state itself, lo = hi).
template <typename T>
struct BallNode {
  T lo_a[kDim], hi_a[kDim], lo_b[kDim], hi_b[kDim];
  unsigned ref_a, ref_b;
};

template <typename T>
struct BallQueryLaunch {
  const BallNode<T>* __restrict__ nodes;
  int root;                                         // node index of the root (>= 0: a non-empty tree)
  int root_is_leaf;                                 // a one-state tree: the root slot holds the state as child a
  int tree_size;                                    // live states
  const unsigned long long* __restrict__ sequence;  // insertion sequence by state id
  const T* __restrict__ queries;                    // kDim coordinates per query
  int count;
  int k;                           // <= kMaxK
  T sphere_radius;                 // BallQueryConfig::sphere_radius
  T radius_growth;                 // BallQueryConfig::radius_growth (> 1)
  int early_exit;                  // BallQueryConfig::early_exit: shrink the radius to the k-th best
  T* __restrict__ best_distance;   // kMaxK per query
  unsigned* __restrict__ best_id;  // kMaxK per query
  int* __restrict__ found;         // states found per query; -1: stack overflow
};

template <typename T>
struct Neighbor {
  T distance;
  unsigned long long sequence;
  unsigned id;
};

template <typename T>
__device__ __forceinline__ bool Before(const Neighbor<T>& a, const Neighbor<T>& b) {
  return a.distance < b.distance || (a.distance == b.distance && a.sequence < b.sequence);
}

template <typename T>
__device__ __forceinline__ T EuclideanDistance(const T* a, const T* q) {
  T sum = T(0);
  for (int i = 0; i < kDim; ++i) {
    const T diff = a[i] - q[i];
    sum += diff * diff;
  }
  return Sqrt(sum);
}

template <typename T>
__device__ __forceinline__ T BoxDistanceSquared(const T* q, const T* lo, const T* hi) {
  T sum = T(0);
  for (int i = 0; i < kDim; ++i) {
    const T d = q[i] < lo[i] ? lo[i] - q[i] : (q[i] > hi[i] ? q[i] - hi[i] : T(0));
    sum += d * d;
  }
  return sum;
}

template <typename T>
__device__ __forceinline__ bool InGrownBox(const T* q, const T* lo, const T* hi, T rho, T margin) {
  const T grow = rho * (T(1) + margin);
  for (int i = 0; i < kDim; ++i)
    if (lo[i] - q[i] > grow || q[i] - hi[i] > grow) return false;
  return true;
}

// The sorted k-best list of one query (Pass::Offer's insertion).
template <typename T>
struct BestList {
  Neighbor<T> items[kMaxK];
  int size;
  int k;
  __device__ __forceinline__ void Offer(const Neighbor<T>& c) {
    int n = size;
    if (n == k) {
      if (!Before(c, items[n - 1])) return;
      n = k - 1;  // the last one drops out
    }
    int pos = n;
#pragma unroll 1
    while (pos > 0 && Before(c, items[pos - 1])) {  // upper_bound: after equal entries
      items[pos] = items[pos - 1];
      --pos;
    }
    items[pos] = c;
    size = n + 1;
  }
};

template <typename T>
struct StackEntry {
  int node;
  T distance_squared;  // P-Sphere: to the node's box; P-Ray: 0
};

template <typename T, bool kSphere>
__device__ __forceinline__ void QueryOne(const BallQueryLaunch<T>& L) {
  const int qi = QueryIndex();
  if (qi >= L.count) return;
  const T kMargin = T(1e-12);  // relative (ball_query_search.cc)
  T q[kDim];
  for (int i = 0; i < kDim; ++i) q[i] = L.queries[qi * kDim + i];
  BestList<T> best;
  best.k = L.k;
  const int want = Min(L.k, L.tree_size);
  StackEntry<T> stack[kBallStackEntries];
  bool overflow = false;
  T rho = L.sphere_radius;
#pragma unroll 1
  while (true) {
    best.size = 0;
    if (L.root_is_leaf) {
      const BallNode<T> root = L.nodes[L.root];
      const T d = EuclideanDistance(root.lo_a, q);
      const unsigned id = root.ref_a & ~kStateBit;
      if (d <= rho) best.Offer(Neighbor<T>{d, L.sequence[id], id});
    } else {
      int top = 0;
      stack[top++] = StackEntry<T>{L.root, T(0)};
#pragma unroll 1
      while (top > 0) {
        const StackEntry<T> e = stack[--top];
        const T radius2 = rho * rho * (T(1) + kMargin);
        if (kSphere && e.distance_squared > radius2) continue;  // dropped without a fetch
        // The node fetch; the compiler loads each box where it is tested, so
        // the references, which every path reads first, carry the marker.
        const BallNode<T>& node = L.nodes[e.node];
        const unsigned refs[2] = {node.ref_a, node.ref_b};  // RC_NODE_FETCH
        bool any = false;
        StackEntry<T> push[2];
        int pushes = 0;
        Neighbor<T> states[2];
        int state_count = 0;
        for (int c = 0; c < 2; ++c) {
          const unsigned ref = refs[c];
          const T* lo = c == 0 ? node.lo_a : node.lo_b;
          const T* hi = c == 0 ? node.hi_a : node.hi_b;
          if (ref & kStateBit) {
            const T d = EuclideanDistance(lo, q);
            if (d <= rho) {
              any = true;
              const unsigned id = ref & ~kStateBit;
              states[state_count++] = Neighbor<T>{d, L.sequence[id], id};
            }
          } else if (kSphere) {
            const T d2 = BoxDistanceSquared(q, lo, hi);
            if (d2 <= radius2) {
              any = true;
              push[pushes++] = StackEntry<T>{static_cast<int>(ref), d2};
            }
          } else if (InGrownBox(q, lo, hi, rho, kMargin)) {
            any = true;
            push[pushes++] = StackEntry<T>{static_cast<int>(ref), T(0)};
          }
        }
        if (!any) continue;  // RETURN_IF #0 of the programs
        if (top + pushes > kBallStackEntries) {
          overflow = true;
          break;
        }
        // The stack pops from the back: the entry to visit second goes first.
        if (pushes == 2) {
          const bool b_first = kSphere && push[1].distance_squared < push[0].distance_squared;
          stack[top++] = b_first ? push[0] : push[1];
          stack[top++] = b_first ? push[1] : push[0];
        } else if (pushes == 1) {
          stack[top++] = push[0];
        }
        for (int s = 0; s < state_count; ++s) best.Offer(states[s]);
        if (L.early_exit && best.size == best.k) rho = Min(rho, best.items[best.size - 1].distance);
      }
    }
    if (overflow || best.size >= want) break;
    rho *= L.radius_growth;  // reaches +inf at worst, which holds every state
  }
#pragma unroll 1
  for (int s = 0; s < best.size; ++s) {
    L.best_distance[qi * kMaxK + s] = best.items[s].distance;
    L.best_id[qi * kMaxK + s] = best.items[s].id;
  }
  L.found[qi] = overflow ? -1 : best.size;
}

}  // namespace rc_cuda

#define RC_BALL_KERNEL(name, T, sphere) \
  extern "C" __global__ void name(rc_cuda::BallQueryLaunch<T> q) { rc_cuda::QueryOne<T, sphere>(q); }
RC_BALL_KERNEL(rc_ball_query_psphere_fp32, float, true)
RC_BALL_KERNEL(rc_ball_query_psphere_fp64, double, true)
RC_BALL_KERNEL(rc_ball_query_pray_fp32, float, false)
RC_BALL_KERNEL(rc_ball_query_pray_fp64, double, false)
#undef RC_BALL_KERNEL
