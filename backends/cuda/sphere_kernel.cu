// The sphere robot on the CUDA cores, one sphere per thread: CollideSphere
// (robocore/collision/sphere_robot.cc) over the flattened box tree, with
// SphereOverlapsAabb at every node (programs/sphere_aabb.asm): the
// squared distance from the centre to the box against the squared radius.
//
// Entry points: rc_sphere_fp32, rc_sphere_fp64.
#include "backends/cuda/box_tree.cuh"
#include "backends/cuda/device_common.cuh"

namespace rc_cuda {

template <typename T>
struct SphereIn {
  T centre[3];  // m
  T radius;     // m
};

template <typename T>
struct SphereLaunch {
  const FlatNode<T>* __restrict__ nodes;
  int node_count;
  const SphereIn<T>* __restrict__ spheres;
  int count;
  TreeResult* __restrict__ results;
};

// SphereOverlapsAabb: ((c - b).cwiseAbs() - h).cwiseMax(0).squaredNorm() <= r^2.
template <typename T>
__device__ __forceinline__ bool SphereOverlapsAabb(const SphereIn<T>& s, const FlatNode<T>& box) {
  T outside[3];
  for (int j = 0; j < 3; ++j) outside[j] = Max(Abs(s.centre[j] - box.centre[j]) - box.half[j], T(0));
  return outside[0] * outside[0] + outside[1] * outside[1] + outside[2] * outside[2] <= s.radius * s.radius;
}

template <typename T>
__device__ __forceinline__ void CollideOneSphere(const SphereLaunch<T>& q) {
  const int i = QueryIndex();
  if (i >= q.count) return;
  const SphereIn<T> sphere = q.spheres[i];
  q.results[i] =
      TraverseTree(q.nodes, q.node_count, [&](const FlatNode<T>& node) { return SphereOverlapsAabb(sphere, node); });
}

}  // namespace rc_cuda

extern "C" __global__ void rc_sphere_fp32(rc_cuda::SphereLaunch<float> q) { rc_cuda::CollideOneSphere(q); }
extern "C" __global__ void rc_sphere_fp64(rc_cuda::SphereLaunch<double> q) { rc_cuda::CollideOneSphere(q); }
