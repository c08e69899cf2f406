#include "workloads/delibot/resampling.h"

#include <cmath>

#include "common/log_domain.h"

namespace rc {

double NormalizeLogWeights(std::vector<double>& log_weights) {
  const double total = LogSumExp(log_weights);
  for (double& w : log_weights) w -= total;
  return total;
}

double EffectiveSampleSize(const std::vector<double>& normalized_log_weights) {
  double sum_sq = 0.0;
  for (double lw : normalized_log_weights) sum_sq += std::exp(2.0 * lw);
  return sum_sq > 0.0 ? 1.0 / sum_sq : 0.0;
}

std::vector<std::size_t> SystematicResample(const std::vector<double>& normalized_log_weights,
                                            double u01, std::size_t output_count) {
  const std::size_t n = normalized_log_weights.size();
  const std::size_t slots = output_count > 0 ? output_count : n;
  std::vector<std::size_t> ancestors(n == 0 ? 0 : slots);
  if (n == 0) return ancestors;
  const double step = 1.0 / static_cast<double>(slots);
  double pointer = u01 * step;
  double cumulative = std::exp(normalized_log_weights[0]);
  std::size_t j = 0;
  for (std::size_t slot = 0; slot < slots; ++slot) {
    // Rounding can leave the final cumulative sum a hair below 1; the last
    // particle then absorbs the remainder instead of running off the end.
    while (pointer > cumulative && j + 1 < n) cumulative += std::exp(normalized_log_weights[++j]);
    ancestors[slot] = j;
    pointer += step;
  }
  return ancestors;
}

}  // namespace rc
