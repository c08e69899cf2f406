#pragma once
// Runs a check on every SIMD path this CPU has (common/cpu_features.h): the
// levels from scalar code up to CpuSimdLevel(), each made the widest in use
// for a scope. Every path must give the same numbers.
#include <vector>

#include "common/cpu_features.h"

namespace rc::test {

inline std::vector<SimdLevel> SimdLevelsThisCpuRuns() {
  std::vector<SimdLevel> levels;
  for (SimdLevel level : {SimdLevel::kScalar, SimdLevel::kAvx2, SimdLevel::kAvx512})
    if (static_cast<int>(level) <= static_cast<int>(CpuSimdLevel())) levels.push_back(level);
  return levels;
}

// Uses at most `level` until the scope ends, then the level in use before.
class ScopedSimdLimit {
 public:
  explicit ScopedSimdLimit(SimdLevel level) : before_(SimdInUse()) { LimitSimd(level); }
  ~ScopedSimdLimit() { LimitSimd(before_); }
  ScopedSimdLimit(const ScopedSimdLimit&) = delete;
  ScopedSimdLimit& operator=(const ScopedSimdLimit&) = delete;

 private:
  SimdLevel before_;
};

}  // namespace rc::test
