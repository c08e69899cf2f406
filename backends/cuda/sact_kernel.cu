// The collision kernel on the CUDA cores, one robot-link OBB per thread:
// CollideBatch's depth-first traversal of the flattened box tree with the
// staged separating-axis test at every node (robocore/collision/sact.cc,
// TestObbAabb with TranslationConvention::kBoxFrame and no sphere
// pre-tests; programs/sact_obb_aabb.asm). The test stops at the first
// separating axis, in the fixed stage order: pre-process, the OBB's three
// face normals, the box's three, the nine edge x edge axes.
//
// The relative rotation R = axes^T and |R| + epsilon depend only on the
// OBB, so the compiler may compute them once per query (the host recomputes
// them per node); the translation t = R d is per node (the asm's PRE).
//
// Entry points: rc_sact_fp32, rc_sact_fp64.
#include "backends/cuda/box_tree.cuh"
#include "backends/cuda/device_common.cuh"

namespace rc_cuda {

// Obb<Scalar> (robocore/collision/obb.h): axes column i = box axis i in
// world coordinates, stored column-major as Eigen does (axes[3 * i + row]).
template <typename T>
struct ObbIn {
  T centre[3];
  T axes[9];
  T half[3];
};

template <typename T>
struct SactLaunch {
  const FlatNode<T>* __restrict__ nodes;
  int node_count;
  const ObbIn<T>* __restrict__ obbs;
  int count;
  T parallel_epsilon;  // SactOptions::parallel_epsilon
  TreeResult* __restrict__ results;
};

// TestObbAabb: true when no axis separates (touching counts as overlap).
template <typename T>
__device__ __forceinline__ bool ObbOverlapsAabb(const ObbIn<T>& obb, const FlatNode<T>& box, T epsilon) {
  // Pre-process: d = c_B - c_A, R_ij = A_i[j], t = R d, |R| + epsilon.
  T d[3], R[3][3], abs_r[3][3], t[3];
  for (int j = 0; j < 3; ++j) d[j] = box.centre[j] - obb.centre[j];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) R[i][j] = obb.axes[3 * i + j];
  for (int i = 0; i < 3; ++i) t[i] = R[i][0] * d[0] + R[i][1] * d[1] + R[i][2] * d[2];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) abs_r[i][j] = Abs(R[i][j]) + epsilon;
  const T* ea = obb.half;
  const T* eb = box.half;
  // Box-normal stage, the OBB's axes.
  for (int i = 0; i < 3; ++i)
    if (Abs(t[i]) > ea[i] + (eb[0] * abs_r[i][0] + eb[1] * abs_r[i][1] + eb[2] * abs_r[i][2])) return false;
  // Box-normal stage, the box's axes (t_b = d).
  for (int j = 0; j < 3; ++j)
    if (Abs(d[j]) > eb[j] + (ea[0] * abs_r[0][j] + ea[1] * abs_r[1][j] + ea[2] * abs_r[2][j])) return false;
  // Edge x edge stage: L = A_i x B_j.
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      const T ra = ea[i1] * abs_r[i2][j] + ea[i2] * abs_r[i1][j];
      const T rb = eb[j1] * abs_r[i][j2] + eb[j2] * abs_r[i][j1];
      if (Abs(t[i2] * R[i1][j] - t[i1] * R[i2][j]) > ra + rb) return false;
    }
  }
  return true;
}

template <typename T>
__device__ __forceinline__ void CollideOneObb(const SactLaunch<T>& q) {
  const int i = QueryIndex();
  if (i >= q.count) return;
  const ObbIn<T> obb = q.obbs[i];
  const T epsilon = q.parallel_epsilon;
  q.results[i] =
      TraverseTree(q.nodes, q.node_count, [&](const FlatNode<T>& node) { return ObbOverlapsAabb(obb, node, epsilon); });
}

}  // namespace rc_cuda

extern "C" __global__ void rc_sact_fp32(rc_cuda::SactLaunch<float> q) { rc_cuda::CollideOneObb(q); }
extern "C" __global__ void rc_sact_fp64(rc_cuda::SactLaunch<double> q) { rc_cuda::CollideOneObb(q); }
