#pragma once
// The instruction sets this CPU runs, and the ones the suite uses, for the
// kernels that pick a SIMD form at run time (robocore/ray_batch_lanes.h,
// backends/key_ranks.h, backends/ray_query_cycles.h). No global -march flag
// is used: each SIMD form is compiled with a function-level target attribute
// and called only where these say so. On targets other than x86-64 the CPU
// runs neither.
//
// Every form gives the same numbers (each is tested against its
// definition), so which one runs changes the host time only. LimitSimd
// lowers the widest form used, process-wide (`rcbench --simd`): to time a
// narrower path on a wider CPU, and to check that every path gives the same
// results on one machine.
#include <string_view>

namespace rc {

// AVX-512 F, VL and DQ (every AVX-512 form in the suite needs at most these).
bool CpuHasAvx512();

// AVX2 (with AVX, SSE4.1; FMA is never used, so it is not asked for).
bool CpuHasAvx2();

// The SIMD forms in increasing width: scalar code, AVX2, AVX-512.
enum class SimdLevel { kScalar = 0, kAvx2 = 1, kAvx512 = 2 };

std::string_view ToString(SimdLevel level);  // "scalar", "avx2", "avx512"
// Reads one of ToString's names; false (and *out untouched) otherwise.
bool ParseSimdLevel(std::string_view text, SimdLevel* out);

// The widest level this CPU runs.
SimdLevel CpuSimdLevel();

// The widest level the suite uses: CpuSimdLevel() unless LimitSimd lowered
// it. Thread-safe; meant to be set once, before any work starts.
SimdLevel SimdInUse();

// Uses at most `level`. Throws std::invalid_argument if the CPU does not run
// it.
void LimitSimd(SimdLevel level);

// Whether the suite uses the AVX-512 (AVX2) forms: the CPU runs them and
// SimdInUse() allows them. The kernels dispatch on these.
bool UseAvx512();
bool UseAvx2();

}  // namespace rc
