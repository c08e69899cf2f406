#pragma once
// Helpers shared by the CUDA kernels under backends/cuda/: one launch
// layout (one query per thread), the scalar overloads, and the marker the
// instruction-count script looks for.
//
// RC_NODE_FETCH: a source line that carries the comment marker
// `RC_NODE_FETCH` loads the node a loop pass fetches (the LOAD micro-op of
// the matching robocore/programs/*.asm). scripts/simt_instruction_counts.py
// finds the instructions the compiler attributes to that line (-lineinfo:
// the address, or the loads) and takes the innermost loop that holds them as
// "one loop pass". Keep the
// node load on its own line with the marker.
//
// Precision: every kernel is a template on its scalar type T and is
// instantiated as float and double. Literals are written T(...) so that the
// float kernels hold no double arithmetic (the script checks it).

namespace rc_cuda {

// One thread per query, 1-D grid: the query index of this thread.
__device__ __forceinline__ int QueryIndex() { return static_cast<int>(blockIdx.x * blockDim.x + threadIdx.x); }

// floor() then a conversion to int, as the host's static_cast<int>(std::floor(x)).
__device__ __forceinline__ int FloorToInt(float x) { return static_cast<int>(floorf(x)); }
__device__ __forceinline__ int FloorToInt(double x) { return static_cast<int>(floor(x)); }

__device__ __forceinline__ float Abs(float x) { return fabsf(x); }
__device__ __forceinline__ double Abs(double x) { return fabs(x); }
__device__ __forceinline__ float Sqrt(float x) { return sqrtf(x); }
__device__ __forceinline__ double Sqrt(double x) { return sqrt(x); }
__device__ __forceinline__ float Exp(float x) { return expf(x); }
__device__ __forceinline__ double Exp(double x) { return exp(x); }
__device__ __forceinline__ float Log(float x) { return logf(x); }
__device__ __forceinline__ double Log(double x) { return log(x); }
template <typename T>
__device__ __forceinline__ T Min(T a, T b) {
  return b < a ? b : a;
}  // std::min's order
template <typename T>
__device__ __forceinline__ T Max(T a, T b) {
  return a < b ? b : a;
}  // std::max's order

}  // namespace rc_cuda
