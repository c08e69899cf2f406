// ray_cast_on_gpu: the device half of the GPU check (docs/gpu_check.md).
//
// Runs the CUDA ray casters that the SIMT model prices
// (backends/cuda/ray_cast_kernels.cu, traversal only) on a real GPU, over
// the batch gpu_ray_cast_export wrote (queries.bin), and for each method x
// order x precision:
//   * checks every answer against the host's: FP64 must equal the host's
//     range and node count bit for bit (the kernels' contract with
//     -fmad=false); FP32 is counted (how many ranges and node counts differ,
//     and by how much at most);
//   * times the launch with CUDA events: warm-up launches, then the median
//     and the minimum of the timed ones.
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
#include "benchmarks/gpu/ray_cast_query_file.h"

namespace {

using rc::gpu_check::RayCastQueryFile;

#define CHECK_CUDA(call)                                                                     \
  do {                                                                                       \
    const cudaError_t status_ = (call);                                                      \
    if (status_ != cudaSuccess) {                                                            \
      std::fprintf(stderr, "ray_cast_on_gpu: %s: %s\n", #call, cudaGetErrorString(status_)); \
      std::exit(1);                                                                          \
    }                                                                                        \
  } while (0)

template <typename T>
T* Upload(const std::vector<T>& host) {
  T* device = nullptr;
  CHECK_CUDA(cudaMalloc(&device, host.size() * sizeof(T)));
  CHECK_CUDA(cudaMemcpy(device, host.data(), host.size() * sizeof(T), cudaMemcpyHostToDevice));
  return device;
}

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

template <typename T>
RayKernel<T> KernelFor(int method);
template <>
RayKernel<double> KernelFor<double>(int method) {
  const RayKernel<double> kernels[] = {rc_march_fp64, rc_dda_fp64, rc_rm_fp64};
  return kernels[method];
}
template <>
RayKernel<float> KernelFor<float>(int method) {
  const RayKernel<float> kernels[] = {rc_march_fp32, rc_dda_fp32, rc_rm_fp32};
  return kernels[method];
}

struct Row {
  std::string method, order, precision;
  std::size_t queries = 0;
  unsigned long long nodes = 0;
  std::size_t range_mismatches = 0, node_mismatches = 0;
  double max_range_diff_m = 0;
  int registers = 0;
  int timed_launches = 0;
  double median_s = 0, min_s = 0;
};

constexpr int kThreadsPerBlock = 256;  // gpu.warps_per_block 8 of the model
// Launches per configuration: warm-ups, then timed ones. `--profile` runs
// one of each, for a profiler that replays every launch (run_on_gpu.sh).
int warmups = 3;
int timed_launches = 21;

template <typename T>
Row RunOne(const RayCastQueryFile& f, int method, bool grid_ordered, const unsigned char* cells, const float* df,
           const DeviceRays<T>& rays, float* range_m, unsigned* nodes) {
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
  const RayKernel<T> kernel = KernelFor<T>(method);
  const int blocks = (n + kThreadsPerBlock - 1) / kThreadsPerBlock;

  Row row;
  row.method = rc::gpu_check::kMethodNames[method];
  row.order = grid_ordered ? "grid" : "random";
  row.precision = sizeof(T) == 8 ? "fp64" : "fp32";
  row.queries = static_cast<std::size_t>(n);
  cudaFuncAttributes attributes{};
  CHECK_CUDA(cudaFuncGetAttributes(&attributes, kernel));
  row.registers = attributes.numRegs;

  cudaEvent_t start, stop;
  CHECK_CUDA(cudaEventCreate(&start));
  CHECK_CUDA(cudaEventCreate(&stop));
  std::vector<double> seconds;
  for (int i = 0; i < warmups + timed_launches; ++i) {
    CHECK_CUDA(cudaEventRecord(start));
    kernel<<<blocks, kThreadsPerBlock>>>(grid, distance, launch);
    CHECK_CUDA(cudaEventRecord(stop));
    CHECK_CUDA(cudaEventSynchronize(stop));
    CHECK_CUDA(cudaGetLastError());
    float ms = 0;
    CHECK_CUDA(cudaEventElapsedTime(&ms, start, stop));
    if (i >= warmups) seconds.push_back(ms * 1e-3);
  }
  CHECK_CUDA(cudaEventDestroy(start));
  CHECK_CUDA(cudaEventDestroy(stop));
  std::sort(seconds.begin(), seconds.end());
  row.timed_launches = static_cast<int>(seconds.size());
  row.median_s = seconds[seconds.size() / 2];
  row.min_s = seconds.front();

  std::vector<float> got_range(n);
  std::vector<unsigned> got_nodes(n);
  CHECK_CUDA(cudaMemcpy(got_range.data(), range_m, n * sizeof(float), cudaMemcpyDeviceToHost));
  CHECK_CUDA(cudaMemcpy(got_nodes.data(), nodes, n * sizeof(unsigned), cudaMemcpyDeviceToHost));
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
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  const bool profile = argc == 4 && std::strcmp(argv[3], "--profile") == 0;
  if (argc != 3 && !profile) {
    std::fprintf(stderr, "usage: ray_cast_on_gpu QUERIES.bin OUT.csv [--profile]\n");
    return 1;
  }
  if (profile) warmups = timed_launches = 1;
  RayCastQueryFile f;
  std::string error;
  if (!rc::gpu_check::ReadQueryFile(argv[1], &f, &error)) {
    std::fprintf(stderr, "ray_cast_on_gpu: %s\n", error.c_str());
    return 1;
  }
  cudaDeviceProp props{};
  CHECK_CUDA(cudaGetDeviceProperties(&props, 0));
  std::printf("device: %s, %d SMs, L2 %d bytes; %zu rays on a %d x %d grid\n", props.name, props.multiProcessorCount,
              props.l2CacheSize, f.queries(), f.size_x, f.size_y);

  unsigned char* cells = Upload(f.cells);
  float* df = Upload(f.distance_m);
  float* range_m = nullptr;
  unsigned* nodes = nullptr;
  CHECK_CUDA(cudaMalloc(&range_m, f.queries() * sizeof(float)));
  CHECK_CUDA(cudaMalloc(&nodes, f.queries() * sizeof(unsigned)));
  const DeviceRays<double> random64 = UploadRays<double>(f, nullptr), grid64 = UploadRays<double>(f, &f.grid_order);
  const DeviceRays<float> random32 = UploadRays<float>(f, nullptr), grid32 = UploadRays<float>(f, &f.grid_order);

  std::vector<Row> rows;
  for (int method = 0; method < rc::gpu_check::kMethodCount; ++method) {
    for (const bool grid_ordered : {false, true}) {
      rows.push_back(
          RunOne<double>(f, method, grid_ordered, cells, df, grid_ordered ? grid64 : random64, range_m, nodes));
      rows.push_back(
          RunOne<float>(f, method, grid_ordered, cells, df, grid_ordered ? grid32 : random32, range_m, nodes));
    }
  }

  FILE* out = std::fopen(argv[2], "w");
  if (!out) {
    std::fprintf(stderr, "ray_cast_on_gpu: %s: cannot open for writing\n", argv[2]);
    return 1;
  }
  std::fprintf(out,
               "device,method,order,precision,queries,nodes,range_mismatches,node_mismatches,max_range_diff_m,"
               "registers,timed_launches,median_s,min_s\n");
  bool fp64_exact = true;
  for (const Row& r : rows) {
    std::fprintf(out, "%s,%s,%s,%s,%zu,%llu,%zu,%zu,%.9g,%d,%d,%.9g,%.9g\n", props.name, r.method.c_str(),
                 r.order.c_str(), r.precision.c_str(), r.queries, r.nodes, r.range_mismatches, r.node_mismatches,
                 r.max_range_diff_m, r.registers, r.timed_launches, r.median_s, r.min_s);
    std::printf("%-5s %-6s %s: %8.1f us median, %8.1f us min, %zu range / %zu node mismatches, %d registers\n",
                r.method.c_str(), r.order.c_str(), r.precision.c_str(), r.median_s * 1e6, r.min_s * 1e6,
                r.range_mismatches, r.node_mismatches, r.registers);
    if (r.precision == "fp64" && (r.range_mismatches != 0 || r.node_mismatches != 0)) fp64_exact = false;
  }
  std::fclose(out);
  if (!fp64_exact) {
    std::fprintf(stderr, "ray_cast_on_gpu: an FP64 answer differs from the host's\n");
    return 3;
  }
  return 0;
}
