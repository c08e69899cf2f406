#include "common/cpu_features.h"

#include <atomic>
#include <stdexcept>
#include <string>

namespace rc {

#if defined(__x86_64__)
bool CpuHasAvx512() {
  static const bool has =
      __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512dq");
  return has;
}

bool CpuHasAvx2() {
  static const bool has = __builtin_cpu_supports("avx2");
  return has;
}
#else
bool CpuHasAvx512() { return false; }
bool CpuHasAvx2() { return false; }
#endif

namespace {

// The ceiling LimitSimd sets; the widest level by default.
std::atomic<int> simd_limit{static_cast<int>(SimdLevel::kAvx512)};

}  // namespace

std::string_view ToString(SimdLevel level) {
  switch (level) {
    case SimdLevel::kScalar: return "scalar";
    case SimdLevel::kAvx2: return "avx2";
    case SimdLevel::kAvx512: return "avx512";
  }
  return "?";
}

bool ParseSimdLevel(std::string_view text, SimdLevel* out) {
  for (SimdLevel level : {SimdLevel::kScalar, SimdLevel::kAvx2, SimdLevel::kAvx512})
    if (text == ToString(level)) return *out = level, true;
  return false;
}

SimdLevel CpuSimdLevel() {
  static const SimdLevel level = CpuHasAvx512() && CpuHasAvx2() ? SimdLevel::kAvx512
                                 : CpuHasAvx2()                 ? SimdLevel::kAvx2
                                                                : SimdLevel::kScalar;
  return level;
}

SimdLevel SimdInUse() {
  const int cpu = static_cast<int>(CpuSimdLevel()), limit = simd_limit.load(std::memory_order_relaxed);
  return static_cast<SimdLevel>(limit < cpu ? limit : cpu);
}

void LimitSimd(SimdLevel level) {
  if (static_cast<int>(level) > static_cast<int>(CpuSimdLevel()))
    throw std::invalid_argument("this CPU does not run " + std::string(ToString(level)) + " (it runs up to " +
                                std::string(ToString(CpuSimdLevel())) + ")");
  simd_limit.store(static_cast<int>(level), std::memory_order_relaxed);
}

bool UseAvx512() { return SimdInUse() == SimdLevel::kAvx512; }
bool UseAvx2() { return SimdInUse() >= SimdLevel::kAvx2; }

}  // namespace rc
