// sact_on_gpu: the device half of the GPU check's collision part
// (docs/gpu_check.md).
//
// Runs the CUDA SACT kernel the SIMT model prices (backends/cuda/
// sact_kernel.cu: one robot-link OBB per thread, depth-first over the
// flattened box tree) on a real GPU, over each scene gpu_sact_export wrote
// (sact_<scene>.bin), as the calibration's batch and as the same OBBs
// repeated kLargeRepeat times, in FP64 and FP32, and for each:
//   * checks every outcome against the host's: FP64 must equal the host's
//     collides, colliding box and node count; FP32 is counted; a stack
//     overflow (the kernel's fixed stack) is counted, never an answer;
//   * times the launch with CUDA events (as ray_cast_on_gpu.cu).
// `--profile` launches each configuration twice (for ncu). Exit status: 0
// when every FP64 outcome matches, 3 when one does not, 1 on a CUDA or
// input error.
//
//   sact_on_gpu OUT.csv [--profile] SACT_FILE...
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <cuda_runtime.h>

#include "backends/cuda/sact_kernel.cu"
#include "benchmarks/gpu/launch_timing.cuh"
#include "benchmarks/gpu/sact_query_file.h"

namespace {

using rc::gpu_check::Upload;

using rc::gpu_check::SactQueryFile;
using rc_cuda::FlatNode;
using rc_cuda::ObbIn;
using rc_cuda::SactLaunch;
using rc_cuda::TreeResult;

constexpr int kLargeRepeat = 16;            // gpu_sact_export's
constexpr int kThreadsPerBlock = 256;       // gpu.warps_per_block 8 of the model
rc::gpu_check::LaunchCounts launch_counts;  // `--profile`: one warm-up, one timed

template <typename T>
std::vector<FlatNode<T>> NodesOf(const SactQueryFile& f) {
  std::vector<FlatNode<T>> nodes(f.nodes());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    for (int j = 0; j < 3; ++j) {
      nodes[i].centre[j] = static_cast<T>(f.node_centre[3 * i + j]);
      nodes[i].half[j] = static_cast<T>(f.node_half[3 * i + j]);
    }
    nodes[i].first_child = f.first_child[i];
    nodes[i].child_count = f.child_count[i];
    nodes[i].depth = f.depth[i];
  }
  return nodes;
}

template <typename T>
std::vector<ObbIn<T>> ObbsOf(const SactQueryFile& f, int repeat) {
  std::vector<ObbIn<T>> obbs;
  for (int r = 0; r < repeat; ++r) {
    for (std::size_t q = 0; q < f.queries(); ++q) {
      ObbIn<T> b;
      for (int j = 0; j < 3; ++j) b.centre[j] = static_cast<T>(f.obb_centre[3 * q + j]);
      for (int j = 0; j < 9; ++j) b.axes[j] = static_cast<T>(f.obb_axes[9 * q + j]);
      for (int j = 0; j < 3; ++j) b.half[j] = static_cast<T>(f.obb_half[3 * q + j]);
      obbs.push_back(b);
    }
  }
  return obbs;
}

struct Row {
  std::string scene, precision;
  int repeat = 1;
  std::size_t queries = 0;
  unsigned long long nodes = 0;
  std::size_t outcome_mismatches = 0, node_mismatches = 0, overflows = 0;
  int registers = 0;
  int timed = 0;
  double median_s = 0, min_s = 0;
};

template <typename T>
Row RunOne(const SactQueryFile& f, int repeat) {
  const std::vector<FlatNode<T>> nodes = NodesOf<T>(f);
  const std::vector<ObbIn<T>> obbs = ObbsOf<T>(f, repeat);
  const int n = static_cast<int>(obbs.size());
  FlatNode<T>* d_nodes = Upload(nodes);
  ObbIn<T>* d_obbs = Upload(obbs);
  TreeResult* d_results = nullptr;
  RC_CHECK_CUDA(cudaMalloc(&d_results, n * sizeof(TreeResult)));
  SactLaunch<T> launch{d_nodes, static_cast<int>(nodes.size()),     d_obbs,
                       n,       static_cast<T>(f.parallel_epsilon), d_results};
  void (*kernel)(SactLaunch<T>) = nullptr;
  if constexpr (sizeof(T) == 8)
    kernel = rc_sact_fp64;
  else
    kernel = rc_sact_fp32;
  const int blocks = (n + kThreadsPerBlock - 1) / kThreadsPerBlock;

  Row row;
  row.scene = f.scene;
  row.precision = sizeof(T) == 8 ? "fp64" : "fp32";
  row.repeat = repeat;
  row.queries = static_cast<std::size_t>(n);
  cudaFuncAttributes attributes{};
  RC_CHECK_CUDA(cudaFuncGetAttributes(&attributes, kernel));
  row.registers = attributes.numRegs;
  const rc::gpu_check::LaunchTimes times =
      rc::gpu_check::TimeLaunches(launch_counts, [&] { kernel<<<blocks, kThreadsPerBlock>>>(launch); });
  row.timed = times.timed;
  row.median_s = times.median_s;
  row.min_s = times.min_s;

  std::vector<TreeResult> got(n);
  RC_CHECK_CUDA(cudaMemcpy(got.data(), d_results, n * sizeof(TreeResult), cudaMemcpyDeviceToHost));
  for (int i = 0; i < n; ++i) {
    const std::size_t q = static_cast<std::size_t>(i) % f.queries();
    row.nodes += got[i].nodes_visited;
    if (got[i].stack_overflow) ++row.overflows;
    if ((got[i].collides != 0) != (f.collides[q] != 0) || got[i].colliding_box != f.colliding_box[q])
      ++row.outcome_mismatches;
    if (got[i].nodes_visited != f.nodes_visited[q]) ++row.node_mismatches;
  }
  RC_CHECK_CUDA(cudaFree(d_nodes));
  RC_CHECK_CUDA(cudaFree(d_obbs));
  RC_CHECK_CUDA(cudaFree(d_results));
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  rc::gpu_check::program_name = "sact_on_gpu";
  int first_file = 2;
  if (argc > 2 && std::strcmp(argv[2], "--profile") == 0) {
    launch_counts.warmups = launch_counts.timed = 1;
    first_file = 3;
  }
  if (argc <= first_file) {
    std::fprintf(stderr, "usage: sact_on_gpu OUT.csv [--profile] SACT_FILE...\n");
    return 1;
  }
  cudaDeviceProp props{};
  RC_CHECK_CUDA(cudaGetDeviceProperties(&props, 0));
  std::vector<Row> rows;
  for (int a = first_file; a < argc; ++a) {
    SactQueryFile f;
    std::string error;
    if (!rc::gpu_check::ReadSactFile(argv[a], &f, &error)) {
      std::fprintf(stderr, "sact_on_gpu: %s\n", error.c_str());
      return 1;
    }
    for (const int repeat : {1, kLargeRepeat}) {
      rows.push_back(RunOne<double>(f, repeat));
      rows.push_back(RunOne<float>(f, repeat));
    }
  }
  FILE* out = std::fopen(argv[1], "w");
  if (!out) {
    std::fprintf(stderr, "sact_on_gpu: %s: cannot open for writing\n", argv[1]);
    return 1;
  }
  std::fprintf(out,
               "device,scene,repeat,precision,queries,nodes,outcome_mismatches,node_mismatches,stack_overflows,"
               "registers,timed_launches,median_s,min_s\n");
  bool fp64_exact = true;
  for (const Row& r : rows) {
    std::fprintf(out, "%s,%s,%d,%s,%zu,%llu,%zu,%zu,%zu,%d,%d,%.9g,%.9g\n", props.name, r.scene.c_str(), r.repeat,
                 r.precision.c_str(), r.queries, r.nodes, r.outcome_mismatches, r.node_mismatches, r.overflows,
                 r.registers, r.timed, r.median_s, r.min_s);
    std::printf("%-13s x%-2d %s: %8.1f us median, %8.1f us min, %zu outcome / %zu node mismatches, %zu overflows\n",
                r.scene.c_str(), r.repeat, r.precision.c_str(), r.median_s * 1e6, r.min_s * 1e6, r.outcome_mismatches,
                r.node_mismatches, r.overflows);
    if (r.precision == "fp64" && (r.outcome_mismatches || r.node_mismatches || r.overflows)) fp64_exact = false;
  }
  std::fclose(out);
  if (!fp64_exact) {
    std::fprintf(stderr, "sact_on_gpu: an FP64 outcome differs from the host's\n");
    return 3;
  }
  return 0;
}
