#pragma once
// What the GPU check's device harnesses (ray_cast_on_gpu.cu,
// sact_on_gpu.cu) share: a CUDA call that fails ends the program with the
// call and the error named (exit 1), an upload, and the timing of a launch.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include <cuda_runtime.h>

namespace rc::gpu_check {

#define RC_CHECK_CUDA(call)                                                                                    \
  do {                                                                                                         \
    const cudaError_t status_ = (call);                                                                        \
    if (status_ != cudaSuccess) {                                                                              \
      std::fprintf(stderr, "%s: %s: %s\n", ::rc::gpu_check::program_name, #call, cudaGetErrorString(status_)); \
      std::exit(1);                                                                                            \
    }                                                                                                          \
  } while (0)

// Set by each harness's main, for the messages above.
inline const char* program_name = "gpu_check";

template <typename T>
T* Upload(const std::vector<T>& host) {
  T* device = nullptr;
  RC_CHECK_CUDA(cudaMalloc(&device, host.size() * sizeof(T)));
  RC_CHECK_CUDA(cudaMemcpy(device, host.data(), host.size() * sizeof(T), cudaMemcpyHostToDevice));
  return device;
}

// Launches per configuration: warm-ups, then timed ones. `--profile` runs
// one of each, for a profiler that replays every launch (run_on_gpu.sh).
struct LaunchCounts {
  int warmups = 3;
  int timed = 21;
};

struct LaunchTimes {
  int timed = 0;
  double median_s = 0, min_s = 0;
};

// Runs `launch` (which enqueues one kernel launch on the default stream)
// counts.warmups + counts.timed times, each between two CUDA events, and
// returns the median and the minimum of the timed ones.
template <typename Launch>
LaunchTimes TimeLaunches(const LaunchCounts& counts, Launch&& launch) {
  cudaEvent_t start, stop;
  RC_CHECK_CUDA(cudaEventCreate(&start));
  RC_CHECK_CUDA(cudaEventCreate(&stop));
  std::vector<double> seconds;
  for (int i = 0; i < counts.warmups + counts.timed; ++i) {
    RC_CHECK_CUDA(cudaEventRecord(start));
    launch();
    RC_CHECK_CUDA(cudaEventRecord(stop));
    RC_CHECK_CUDA(cudaEventSynchronize(stop));
    RC_CHECK_CUDA(cudaGetLastError());
    float ms = 0;
    RC_CHECK_CUDA(cudaEventElapsedTime(&ms, start, stop));
    if (i >= counts.warmups) seconds.push_back(ms * 1e-3);
  }
  RC_CHECK_CUDA(cudaEventDestroy(start));
  RC_CHECK_CUDA(cudaEventDestroy(stop));
  std::sort(seconds.begin(), seconds.end());
  LaunchTimes t;
  t.timed = static_cast<int>(seconds.size());
  t.median_s = seconds[seconds.size() / 2];
  t.min_s = seconds.front();
  return t;
}

}  // namespace rc::gpu_check
