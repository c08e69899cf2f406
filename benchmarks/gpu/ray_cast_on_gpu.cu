// ray_cast_on_gpu: the device half of the GPU check (docs/gpu_check.md).
//
// Runs the CUDA ray casters that the SIMT model prices
// (backends/cuda/ray_cast_kernels.cu) on a real GPU, over
// the batch gpu_ray_cast_export wrote (queries.bin), and for each method x
// order x precision, and with a leaf file (leaf.bin) for each method x beam
// leaf (max-log, exact) x precision in random order:
//   * checks every answer against the host's: FP64 must equal the host's
//     range and node count bit for bit (the kernels' contract with
//     -fmad=false); FP32 is counted (how many ranges and node counts differ,
//     and by how much at most);
//   * times the launch with CUDA events: warm-up launches, then the median
//     and the minimum of the timed ones.
// With a leaf, the log densities are compared with the host's exact ones
// (counted, not required to match: the GPU's exp and log are not glibc's).
// `--profile` launches each configuration twice (for ncu).
// Writes one CSV row per launch configuration. Exit status: 0 when every
// FP64 answer matches, 3 when one does not, 1 on a CUDA or input error.
//
// Build (run_on_gpu.sh does this):
//   nvcc -O3 -arch=sm_90 -fmad=false -std=c++17 -I. benchmarks/gpu/ray_cast_on_gpu.cu -o ray_cast_on_gpu
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <cuda_runtime.h>

#include "backends/cuda/ray_cast_kernels.cu"
#include "benchmarks/gpu/beam_leaf_file.h"
#include "benchmarks/gpu/launch_timing.cuh"
#include "benchmarks/gpu/ray_cast_query_file.h"

namespace {

using rc::gpu_check::Upload;

using rc::gpu_check::BeamLeafFile;
using rc::gpu_check::RayCastQueryFile;

// The batch's rays in one order and precision, on the device.
template <typename T>
struct DeviceRays {
  T *origin_x = nullptr, *origin_y = nullptr, *dir_x = nullptr, *dir_y = nullptr;
};

template <typename T>
DeviceRays<T> UploadRays(const RayCastQueryFile& f, const std::vector<std::uint32_t>* order) {
  const std::size_t n = f.queries();
  std::vector<T> ox(n), oy(n), dx(n), dy(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t q = order ? (*order)[i] : i;
    ox[i] = static_cast<T>(f.origin_x[q]);
    oy[i] = static_cast<T>(f.origin_y[q]);
    dx[i] = static_cast<T>(f.dir_x[q]);
    dy[i] = static_cast<T>(f.dir_y[q]);
  }
  return {Upload(ox), Upload(oy), Upload(dx), Upload(dy)};
}

template <typename T>
using RayKernel = void (*)(Grid<T>, DistanceCells, RayLaunch<T>);

// The kernel of a method (march, dda, rm) with a leaf (Leaf::kNone,
// kMaxLog, kExact).
template <typename T>
RayKernel<T> KernelFor(int method, Leaf leaf);
template <>
RayKernel<double> KernelFor<double>(int method, Leaf leaf) {
  const RayKernel<double> kernels[3][3] = {{rc_march_fp64, rc_march_beam_fp64, rc_march_beam_exact_fp64},
                                           {rc_dda_fp64, rc_dda_beam_fp64, rc_dda_beam_exact_fp64},
                                           {rc_rm_fp64, rc_rm_beam_fp64, rc_rm_beam_exact_fp64}};
  return kernels[method][static_cast<int>(leaf)];
}
template <>
RayKernel<float> KernelFor<float>(int method, Leaf leaf) {
  const RayKernel<float> kernels[3][3] = {{rc_march_fp32, rc_march_beam_fp32, rc_march_beam_exact_fp32},
                                          {rc_dda_fp32, rc_dda_beam_fp32, rc_dda_beam_exact_fp32},
                                          {rc_rm_fp32, rc_rm_beam_fp32, rc_rm_beam_exact_fp32}};
  return kernels[method][static_cast<int>(leaf)];
}

const char* LeafName(Leaf leaf) { return leaf == Leaf::kNone ? "none" : (leaf == Leaf::kMaxLog ? "maxlog" : "exact"); }

// The beam model's parameters and the max-log leaf's constants
// (beam_leaf.cuh), in the kernel's scalar type.
template <typename T>
rc_cuda::BeamParams<T> BeamParamsOf(const BeamLeafFile& f) {
  rc_cuda::BeamParams<T> p{};
  p.z_hit = static_cast<T>(f.z_hit);
  p.z_short = static_cast<T>(f.z_short);
  p.z_max = static_cast<T>(f.z_max);
  p.z_rand = static_cast<T>(f.z_rand);
  p.sigma_hit_m = static_cast<T>(f.sigma_hit_m);
  p.lambda_short_per_m = static_cast<T>(f.lambda_short_per_m);
  p.max_range_m = static_cast<T>(f.max_range_m);
  p.neg_half_inv_var = static_cast<T>(-1.0 / (2.0 * f.sigma_hit_m * f.sigma_hit_m));
  p.neg_lambda = static_cast<T>(-f.lambda_short_per_m);
  p.log_z_hit = static_cast<T>(std::log(f.z_hit / (f.sigma_hit_m * std::sqrt(2.0 * M_PI))));
  p.log_z_rand = static_cast<T>(std::log(f.z_rand / f.max_range_m));
  p.log_z_max = static_cast<T>(std::log(f.z_max));
  return p;
}

struct Row {
  std::string method, order, leaf, precision;
  std::size_t queries = 0;
  unsigned long long nodes = 0;
  std::size_t range_mismatches = 0, node_mismatches = 0;
  double max_range_diff_m = 0;
  // With a leaf: log densities that differ from the host's exact
  // BeamLogDensity, and the largest difference (for the max-log leaf, how
  // far the approximation is from the exact density).
  std::size_t log_density_differs = 0;
  double max_log_density_diff = 0;
  int registers = 0;
  int timed_launches = 0;
  double median_s = 0, min_s = 0;
};

constexpr int kThreadsPerBlock = 256;       // gpu.warps_per_block 8 of the model
rc::gpu_check::LaunchCounts launch_counts;  // `--profile`: one warm-up, one timed

// The leaf's inputs on the device (null without a leaf file).
template <typename T>
struct DeviceLeaf {
  const BeamLeafFile* file = nullptr;
  T* measured_m = nullptr;
  T* log_density = nullptr;
};

template <typename T>
Row RunOne(const RayCastQueryFile& f, int method, bool grid_ordered, Leaf leaf_kind, const unsigned char* cells,
           const float* df, const DeviceRays<T>& rays, const DeviceLeaf<T>& leaf, float* range_m, unsigned* nodes) {
  const int n = static_cast<int>(f.queries());
  Grid<T> grid{cells, f.size_x, f.size_y, static_cast<T>(f.resolution_m)};
  DistanceCells distance{df};
  RayLaunch<T> launch{};
  launch.origin_x = rays.origin_x;
  launch.origin_y = rays.origin_y;
  launch.dir_x = rays.dir_x;
  launch.dir_y = rays.dir_y;
  launch.count = n;
  launch.max_range_m = static_cast<T>(f.max_range_m);
  launch.range_m = range_m;
  launch.nodes = nodes;
  if (leaf_kind != Leaf::kNone) {
    launch.measured_m = leaf.measured_m;
    launch.log_density = leaf.log_density;
    launch.beam = BeamParamsOf<T>(*leaf.file);
  }
  const RayKernel<T> kernel = KernelFor<T>(method, leaf_kind);
  const int blocks = (n + kThreadsPerBlock - 1) / kThreadsPerBlock;

  Row row;
  row.method = rc::gpu_check::kMethodNames[method];
  row.order = grid_ordered ? "grid" : "random";
  row.leaf = LeafName(leaf_kind);
  row.precision = sizeof(T) == 8 ? "fp64" : "fp32";
  row.queries = static_cast<std::size_t>(n);
  cudaFuncAttributes attributes{};
  RC_CHECK_CUDA(cudaFuncGetAttributes(&attributes, kernel));
  row.registers = attributes.numRegs;

  const rc::gpu_check::LaunchTimes times =
      rc::gpu_check::TimeLaunches(launch_counts, [&] { kernel<<<blocks, kThreadsPerBlock>>>(grid, distance, launch); });
  row.timed_launches = times.timed;
  row.median_s = times.median_s;
  row.min_s = times.min_s;

  std::vector<float> got_range(n);
  std::vector<unsigned> got_nodes(n);
  RC_CHECK_CUDA(cudaMemcpy(got_range.data(), range_m, n * sizeof(float), cudaMemcpyDeviceToHost));
  RC_CHECK_CUDA(cudaMemcpy(got_nodes.data(), nodes, n * sizeof(unsigned), cudaMemcpyDeviceToHost));
  const rc::gpu_check::HostAnswers& host = f.host[method];
  for (int i = 0; i < n; ++i) {
    const std::size_t q = grid_ordered ? f.grid_order[i] : static_cast<std::size_t>(i);
    row.nodes += got_nodes[i];
    if (std::memcmp(&got_range[i], &host.range_m[q], sizeof(float)) != 0) {
      ++row.range_mismatches;
      row.max_range_diff_m = std::max(row.max_range_diff_m, std::fabs(double(got_range[i]) - double(host.range_m[q])));
    }
    if (got_nodes[i] != host.nodes[q]) ++row.node_mismatches;
  }
  if (leaf_kind != Leaf::kNone) {
    std::vector<T> got_log(n);
    RC_CHECK_CUDA(cudaMemcpy(got_log.data(), leaf.log_density, n * sizeof(T), cudaMemcpyDeviceToHost));
    const std::vector<double>& expected = leaf.file->host_log_density[method];
    for (int i = 0; i < n; ++i) {  // the leaf runs in random (query) order
      const double got = static_cast<double>(got_log[i]);
      if (got != expected[i]) {
        ++row.log_density_differs;
        row.max_log_density_diff = std::max(row.max_log_density_diff, std::fabs(got - expected[i]));
      }
    }
  }
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  rc::gpu_check::program_name = "ray_cast_on_gpu";
  bool profile = false;
  const char* leaf_path = nullptr;
  bool usage = argc < 3;
  for (int a = 3; a < argc; ++a) {
    if (std::strcmp(argv[a], "--profile") == 0)
      profile = true;
    else if (!leaf_path)
      leaf_path = argv[a];
    else
      usage = true;  // one leaf file at most
  }
  if (usage) {
    std::fprintf(stderr, "usage: ray_cast_on_gpu QUERIES.bin OUT.csv [--profile] [LEAF.bin]\n");
    return 1;
  }
  if (profile) launch_counts.warmups = launch_counts.timed = 1;
  RayCastQueryFile f;
  BeamLeafFile leaf_file;
  std::string error;
  if (!rc::gpu_check::ReadQueryFile(argv[1], &f, &error) ||
      (leaf_path && !rc::gpu_check::ReadBeamLeafFile(leaf_path, &leaf_file, &error))) {
    std::fprintf(stderr, "ray_cast_on_gpu: %s\n", error.c_str());
    return 1;
  }
  if (leaf_path && leaf_file.queries() != f.queries()) {
    std::fprintf(stderr, "ray_cast_on_gpu: %s: queries: %zu, but %s has %zu\n", leaf_path, leaf_file.queries(), argv[1],
                 f.queries());
    return 1;
  }
  cudaDeviceProp props{};
  RC_CHECK_CUDA(cudaGetDeviceProperties(&props, 0));
  std::printf("device: %s, %d SMs, L2 %d bytes; %zu rays on a %d x %d grid\n", props.name, props.multiProcessorCount,
              props.l2CacheSize, f.queries(), f.size_x, f.size_y);

  unsigned char* cells = Upload(f.cells);
  float* df = Upload(f.distance_m);
  float* range_m = nullptr;
  unsigned* nodes = nullptr;
  RC_CHECK_CUDA(cudaMalloc(&range_m, f.queries() * sizeof(float)));
  RC_CHECK_CUDA(cudaMalloc(&nodes, f.queries() * sizeof(unsigned)));
  const DeviceRays<double> random64 = UploadRays<double>(f, nullptr), grid64 = UploadRays<double>(f, &f.grid_order);
  const DeviceRays<float> random32 = UploadRays<float>(f, nullptr), grid32 = UploadRays<float>(f, &f.grid_order);

  DeviceLeaf<double> leaf64;
  DeviceLeaf<float> leaf32;
  if (leaf_path) {
    leaf64.file = leaf32.file = &leaf_file;
    std::vector<float> measured32(leaf_file.measured_m.begin(), leaf_file.measured_m.end());
    leaf64.measured_m = Upload(leaf_file.measured_m);
    leaf32.measured_m = Upload(measured32);
    RC_CHECK_CUDA(cudaMalloc(&leaf64.log_density, f.queries() * sizeof(double)));
    RC_CHECK_CUDA(cudaMalloc(&leaf32.log_density, f.queries() * sizeof(float)));
  }

  // The traversal alone, in both orders, first (report.py reads the
  // profile's launches in this order); then, with a leaf file, each method
  // with its two leaves, in random order.
  std::vector<Row> rows;
  for (int method = 0; method < rc::gpu_check::kMethodCount; ++method) {
    for (const bool grid_ordered : {false, true}) {
      rows.push_back(RunOne<double>(f, method, grid_ordered, Leaf::kNone, cells, df, grid_ordered ? grid64 : random64,
                                    leaf64, range_m, nodes));
      rows.push_back(RunOne<float>(f, method, grid_ordered, Leaf::kNone, cells, df, grid_ordered ? grid32 : random32,
                                   leaf32, range_m, nodes));
    }
  }
  if (leaf_path) {
    for (int method = 0; method < rc::gpu_check::kMethodCount; ++method) {
      for (const Leaf leaf_kind : {Leaf::kMaxLog, Leaf::kExact}) {
        rows.push_back(RunOne<double>(f, method, false, leaf_kind, cells, df, random64, leaf64, range_m, nodes));
        rows.push_back(RunOne<float>(f, method, false, leaf_kind, cells, df, random32, leaf32, range_m, nodes));
      }
    }
  }

  FILE* out = std::fopen(argv[2], "w");
  if (!out) {
    std::fprintf(stderr, "ray_cast_on_gpu: %s: cannot open for writing\n", argv[2]);
    return 1;
  }
  std::fprintf(out,
               "device,method,order,leaf,precision,queries,nodes,range_mismatches,node_mismatches,max_range_diff_m,"
               "log_density_differs,max_log_density_diff,registers,timed_launches,median_s,min_s\n");
  bool fp64_exact = true;
  for (const Row& r : rows) {
    std::fprintf(out, "%s,%s,%s,%s,%s,%zu,%llu,%zu,%zu,%.9g,%zu,%.9g,%d,%d,%.9g,%.9g\n", props.name, r.method.c_str(),
                 r.order.c_str(), r.leaf.c_str(), r.precision.c_str(), r.queries, r.nodes, r.range_mismatches,
                 r.node_mismatches, r.max_range_diff_m, r.log_density_differs, r.max_log_density_diff, r.registers,
                 r.timed_launches, r.median_s, r.min_s);
    std::printf(
        "%-5s %-6s %-6s %s: %8.1f us median, %8.1f us min, %zu range / %zu node mismatches, %zu log densities "
        "differ (max %.3g), %d registers\n",
        r.method.c_str(), r.order.c_str(), r.leaf.c_str(), r.precision.c_str(), r.median_s * 1e6, r.min_s * 1e6,
        r.range_mismatches, r.node_mismatches, r.log_density_differs, r.max_log_density_diff, r.registers);
    if (r.precision == "fp64" && (r.range_mismatches != 0 || r.node_mismatches != 0)) fp64_exact = false;
  }
  std::fclose(out);
  if (!fp64_exact) {
    std::fprintf(stderr, "ray_cast_on_gpu: an FP64 answer differs from the host's\n");
    return 3;
  }
  return 0;
}
