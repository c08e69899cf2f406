#include "common/cpu_features.h"

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

}  // namespace rc
