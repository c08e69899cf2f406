#pragma once
// Resampling policy: systematic (low-variance) resampling, triggered when the
// effective sample size falls below a fraction of the particle count (MRPT
// and AMCL practice; 0.5 by default).
#include <cstddef>
#include <vector>

namespace rc {

// Normalizes log weights in place with log-sum-exp so that
// sum(exp(log_weights)) == 1, and returns the log of the former total.
double NormalizeLogWeights(std::vector<double>& log_weights);

// Effective sample size 1 / sum(w^2) of normalized log weights, in [1, N].
double EffectiveSampleSize(const std::vector<double>& normalized_log_weights);

// Systematic resampling: one uniform offset u in [0, 1/N) and N equally spaced
// pointers; returns the chosen ancestor index for each of the N slots. N is
// the input size unless `output_count` is given (a large initial set for
// global localization is reduced to the working size this way).
std::vector<std::size_t> SystematicResample(const std::vector<double>& normalized_log_weights,
                                            double u01, std::size_t output_count = 0);

}  // namespace rc
