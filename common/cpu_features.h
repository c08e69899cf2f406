#pragma once
// The instruction sets this CPU runs, for the kernels that pick a SIMD form
// at run time (robocore/ray_batch_lanes.h, backends/key_ranks.h,
// backends/ray_query_cycles.h). No global -march flag is used: each SIMD
// form is compiled with a function-level target attribute and called only
// where these say the CPU has it. Both are false on targets other than
// x86-64.
namespace rc {

// AVX-512 F, VL and DQ (every AVX-512 form in the suite needs at most these).
bool CpuHasAvx512();

// AVX2 (with AVX, SSE4.1; FMA is never used, so it is not asked for).
bool CpuHasAvx2();

}  // namespace rc
