#pragma once
// Log-domain arithmetic for particle weights. A 180-beam scan likelihood is a
// product of 180 densities: RoWild multiplies them directly, its best weights
// reach about 1e-268 and in 407 of 712 updates all of them underflow to 0 and
// turn into NaN. Summing logs and normalizing with log-sum-exp cannot
// underflow that way.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace rc {

// log(sum(exp(v))) computed stably; -inf for an empty input or all -inf.
inline double LogSumExp(const std::vector<double>& v) {
  double m = -std::numeric_limits<double>::infinity();
  for (double x : v) m = std::max(m, x);
  if (!std::isfinite(m)) return m;
  double s = 0.0;
  for (double x : v) s += std::exp(x - m);
  return m + std::log(s);
}

// log(exp(a) + exp(b)).
inline double LogAddExp(double a, double b) {
  if (a < b) std::swap(a, b);
  if (!std::isfinite(b)) return a;
  return a + std::log1p(std::exp(b - a));
}

}  // namespace rc
