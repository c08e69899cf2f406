// DeliBot's ray casters on the CUDA cores, one ray per thread: CastMarch,
// CastDda and CastRayMarching of robocore/ray_cast.h, statement for
// statement, with the programs' inputs (grid_march.asm, dda_step.asm,
// rm_step.asm: origin and unit direction per ray), and optionally a beam
// leaf (beam_leaf.cuh) after the traversal: the max-log leaf of
// beam_leaf.asm (_beam) or the host's exact density (_beam_exact).
//
// Given the host's origins and directions, the double kernels compute the
// host's ranges bit for bit when compiled with -fmad=false (the host build
// has no FMA contraction): every division, floor and conversion is the
// host's, in the host's order. The direction is an input (the programs take
// d), so the host's cos/sin is not redone here.
//
// Entry points (extern "C", one per method, leaf and precision):
//   rc_{march,dda,rm}[_beam|_beam_exact]_{fp32,fp64}
#include "backends/cuda/beam_leaf.cuh"
#include "backends/cuda/device_common.cuh"

namespace rc_cuda {

// OccupancyGrid (maps/occupancy_grid.h): one byte per cell (CellState,
// 0 = free), cell (ix, iy) at ix * size_y + iy.
template <typename T>
struct Grid {
  const unsigned char* __restrict__ cells;
  int size_x;
  int size_y;
  T resolution_m;  // m
};

// DistanceField (maps/distance_field.h): one float per cell, same indexing.
struct DistanceCells {
  const float* __restrict__ distance_m;
};

// A batch of rays (RayBatch) and where the answers go.
template <typename T>
struct RayLaunch {
  const T* __restrict__ origin_x;  // m
  const T* __restrict__ origin_y;  // m
  const T* __restrict__ dir_x;     // unit direction
  const T* __restrict__ dir_y;
  int count;
  T max_range_m;                 // m
  float* __restrict__ range_m;   // RayHit::range_m
  unsigned* __restrict__ nodes;  // RayHit::nodes
  // The beam leaf: the measured range of each ray and its log density.
  const T* __restrict__ measured_m;
  T* __restrict__ log_density;
  BeamParams<T> beam;
};

struct RayHit {
  float range_m;
  unsigned nodes;
};

template <typename T>
__device__ __forceinline__ bool Contains(const Grid<T>& g, int ix, int iy) {
  return ix >= 0 && iy >= 0 && ix < g.size_x && iy < g.size_y;
}

template <typename T>
__device__ __forceinline__ unsigned long long CellIndex(const Grid<T>& g, int ix, int iy) {
  return static_cast<unsigned long long>(ix) * static_cast<unsigned long long>(g.size_y) +
         static_cast<unsigned long long>(iy);
}

// ray_cast_detail::Axis: per-axis traversal state from the origin.
template <typename T>
struct Axis {
  T origin;
  T dir;
  T inv_dir;  // 1 / dir (0 when dir is 0)
  int step;   // +1, -1 or 0
  __device__ __forceinline__ T BoundaryTime(int cell, T r) const {
    if (step == 0) return T(INFINITY);
    const int boundary = step > 0 ? cell + 1 : cell;
    return (boundary * r - origin) * inv_dir;
  }
  __device__ __forceinline__ T EntryTime(int cell, T r) const {
    if (step == 0) return -T(INFINITY);
    const int boundary = step > 0 ? cell : cell + 1;
    return (boundary * r - origin) * inv_dir;
  }
};

template <typename T>
__device__ __forceinline__ Axis<T> MakeAxis(T origin, T dir) {
  Axis<T> a;
  a.origin = origin;
  a.dir = dir;
  a.step = dir > T(0) ? 1 : (dir < T(0) ? -1 : 0);
  a.inv_dir = a.step == 0 ? T(0) : T(1) / dir;
  return a;
}

template <typename T>
__device__ __forceinline__ RayHit CastMarch(const Grid<T>& g, T ox, T oy, T dx, T dy, T max_range) {
  const T r = g.resolution_m;
  RayHit hit{0.0f, 0u};
  const long long steps = static_cast<long long>(floor(max_range / r));
#pragma unroll 1
  for (long long k = 0; k <= steps; ++k) {
    const T t = k * r;
    const int ix = FloorToInt((ox + t * dx) / r);
    const int iy = FloorToInt((oy + t * dy) / r);
    if (!Contains(g, ix, iy)) {
      hit.range_m = static_cast<float>(t);
      return hit;
    }
    const unsigned char cell = g.cells[CellIndex(g, ix, iy)];  // RC_NODE_FETCH
    ++hit.nodes;
    if (cell != 0) {
      hit.range_m = static_cast<float>(t);
      return hit;
    }
  }
  hit.range_m = static_cast<float>(max_range);
  return hit;
}

template <typename T>
__device__ __forceinline__ RayHit CastDda(const Grid<T>& g, T ox, T oy, T dx, T dy, T max_range) {
  const T r = g.resolution_m;
  const Axis<T> ax = MakeAxis(ox, dx);
  const Axis<T> ay = MakeAxis(oy, dy);
  int ix = FloorToInt(ox / r);
  int iy = FloorToInt(oy / r);
  RayHit hit{0.0f, 0u};
  T t_enter = T(0);
#pragma unroll 1
  while (true) {
    if (t_enter >= max_range) {
      hit.range_m = static_cast<float>(max_range);
      return hit;
    }
    if (!Contains(g, ix, iy)) {
      hit.range_m = static_cast<float>(t_enter);
      return hit;
    }
    const unsigned char cell = g.cells[CellIndex(g, ix, iy)];  // RC_NODE_FETCH
    ++hit.nodes;
    if (cell != 0) {
      hit.range_m = static_cast<float>(t_enter);
      return hit;
    }
    const T tx = ax.BoundaryTime(ix, r), ty = ay.BoundaryTime(iy, r);
    // Ties step x first (CastDda's corner rule).
    if (tx <= ty) {
      ix += ax.step;
      t_enter = tx;
    } else {
      iy += ay.step;
      t_enter = ty;
    }
  }
}

template <typename T>
__device__ __forceinline__ RayHit CastRayMarching(const Grid<T>& g, const DistanceCells& df, T ox, T oy, T dx, T dy,
                                                  T max_range) {
  const T r = g.resolution_m;
  const Axis<T> ax = MakeAxis(ox, dx);
  const Axis<T> ay = MakeAxis(oy, dy);
  const T kJumpMargin = (Sqrt(T(2)) + T(0.5)) * r;
  int ix = FloorToInt(ox / r);
  int iy = FloorToInt(oy / r);
  RayHit hit{0.0f, 0u};
  T t_enter = T(0);
#pragma unroll 1
  while (true) {
    if (t_enter >= max_range) {
      hit.range_m = static_cast<float>(max_range);
      return hit;
    }
    if (!Contains(g, ix, iy)) {
      hit.range_m = static_cast<float>(t_enter);
      return hit;
    }
    const T d = df.distance_m[CellIndex(g, ix, iy)];  // RC_NODE_FETCH
    ++hit.nodes;
    if (d == T(0)) {
      hit.range_m = static_cast<float>(t_enter);
      return hit;
    }
    const T tx = ax.BoundaryTime(ix, r), ty = ay.BoundaryTime(iy, r);
    const T t_exit = Min(tx, ty);
    const T jump = d - kJumpMargin;
    if (jump > r) {
      const T t_land = t_enter + jump;
      const int jx = FloorToInt((ox + t_land * ax.dir) / r);
      const int jy = FloorToInt((oy + t_land * ay.dir) / r);
      const T t_in = Max(ax.EntryTime(jx, r), ay.EntryTime(jy, r));
      const T t_out = Min(ax.BoundaryTime(jx, r), ay.BoundaryTime(jy, r));
      if (t_in < t_out && t_in > t_enter) {
        ix = jx;
        iy = jy;
        t_enter = t_in;
        continue;
      }
    }
    if (tx <= ty) {
      ix += ax.step;
    } else {
      iy += ay.step;
    }
    t_enter = t_exit;
  }
}

enum class Method { kMarch, kDda, kRayMarching };
enum class Leaf { kNone, kMaxLog, kExact };

template <typename T, Method kMethod, Leaf kLeaf>
__device__ __forceinline__ void CastOneRay(const Grid<T>& g, const DistanceCells& df, const RayLaunch<T>& q) {
  const int i = QueryIndex();
  if (i >= q.count) return;
  const T ox = q.origin_x[i], oy = q.origin_y[i], dx = q.dir_x[i], dy = q.dir_y[i];
  RayHit hit;
  if (kMethod == Method::kMarch)
    hit = CastMarch(g, ox, oy, dx, dy, q.max_range_m);
  else if (kMethod == Method::kDda)
    hit = CastDda(g, ox, oy, dx, dy, q.max_range_m);
  else
    hit = CastRayMarching(g, df, ox, oy, dx, dy, q.max_range_m);
  q.range_m[i] = hit.range_m;
  q.nodes[i] = hit.nodes;
  // The beam leaf scores the float range, as the host scores RayHit::range_m.
  if (kLeaf == Leaf::kMaxLog)
    q.log_density[i] = MaxLogBeamLogDensity(q.beam, q.measured_m[i], static_cast<T>(hit.range_m));
  if (kLeaf == Leaf::kExact) q.log_density[i] = BeamLogDensity(q.beam, q.measured_m[i], static_cast<T>(hit.range_m));
}

}  // namespace rc_cuda

using rc_cuda::DistanceCells;
using rc_cuda::Grid;
using rc_cuda::Leaf;
using rc_cuda::Method;
using rc_cuda::RayLaunch;

#define RC_RAY_KERNEL(name, T, method, leaf)                                           \
  extern "C" __global__ void name(Grid<T> grid, DistanceCells df, RayLaunch<T> rays) { \
    rc_cuda::CastOneRay<T, method, leaf>(grid, df, rays);                              \
  }
#define RC_RAY_KERNELS(prefix, method)                                 \
  RC_RAY_KERNEL(prefix##_fp32, float, method, Leaf::kNone)             \
  RC_RAY_KERNEL(prefix##_fp64, double, method, Leaf::kNone)            \
  RC_RAY_KERNEL(prefix##_beam_fp32, float, method, Leaf::kMaxLog)      \
  RC_RAY_KERNEL(prefix##_beam_fp64, double, method, Leaf::kMaxLog)     \
  RC_RAY_KERNEL(prefix##_beam_exact_fp32, float, method, Leaf::kExact) \
  RC_RAY_KERNEL(prefix##_beam_exact_fp64, double, method, Leaf::kExact)
RC_RAY_KERNELS(rc_march, Method::kMarch)
RC_RAY_KERNELS(rc_dda, Method::kDda)
RC_RAY_KERNELS(rc_rm, Method::kRayMarching)
#undef RC_RAY_KERNELS
#undef RC_RAY_KERNEL
