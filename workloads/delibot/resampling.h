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
// pointers; returns the chosen ancestor index for each of the N slots.
std::vector<std::size_t> SystematicResample(const std::vector<double>& normalized_log_weights,
                                            double u01);

}  // namespace rc
