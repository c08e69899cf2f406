#pragma once
// Resampling policy: systematic (low-variance) resampling, triggered when the
// effective sample size falls below a fraction of the particle count (MRPT
// and AMCL practice; 0.5 by default).
#include <cstddef>
#include <functional>
#include <vector>

#include "workloads/delibot/hypothesis_clusters.h"

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
std::vector<std::size_t> SystematicResample(const std::vector<double>& normalized_log_weights, double u01,
                                            std::size_t output_count = 0);

// Hypothesis-preserving resampling (after Milstein et al., "Robust global
// localization using clustered particle filtering", AAAI 2002). Plain
// resampling gives a hypothesis particles in proportion to its posterior
// mass, so a hypothesis that trails by a few nats for a few updates is left
// with no particle and can never come back, however strongly the later scans
// favour it. Here every cluster whose mass is within window_nats of the
// heaviest cluster's keeps at least min_particles particles; each of them
// carries the weight mass / min_particles, so the weighted set still
// represents the same posterior (only where the particles sit changes). The
// other clusters share the remaining slots by one systematic pass, with
// equal weights. At most half of the slots go to the floor (the heaviest
// eligible clusters first). With one cluster this is SystematicResample.
struct HypothesisFloor {
  int min_particles = 0;     // particles a kept hypothesis holds at least; 0 = off
  double window_nats = 0.0;  // kept while log(mass) >= log(heaviest mass) - window_nats
};

struct WeightedResample {
  std::vector<std::size_t> ancestors;  // one per output slot
  std::vector<double> log_weights;     // normalized, one per output slot
  int floored_clusters = 0;            // clusters held at min_particles
  // The first shared_slots slots come from the shared pass and carry equal
  // weights; the rest belong to floored clusters. Right after a floored
  // resampling the effective sample size is about shared_slots (at least
  // half the slots), not N: the floored particles carry little weight.
  std::size_t shared_slots = 0;
};

// Log of each cluster's total weight (-inf for a cluster of zero weight).
// Throws std::invalid_argument if the clusters do not cover the weights.
std::vector<double> ClusterLogMasses(const std::vector<double>& normalized_log_weights,
                                     const HypothesisClusters& clusters);

// Hypotheses alive: clusters whose log mass is within window_nats of the
// heaviest (the heaviest included; 0 for an empty set). These are the ones
// the floor keeps, and while more than one is alive the belief has a rival.
int HypothesesAlive(const std::vector<double>& cluster_log_masses, double window_nats);

// u01(k) is the offset in [0, 1) of systematic pass k: 0 for the shared pass,
// k >= 1 for the k-th floored cluster (heaviest first).
WeightedResample HypothesisPreservingResample(const std::vector<double>& normalized_log_weights,
                                              const HypothesisClusters& clusters, std::size_t output_count,
                                              const HypothesisFloor& floor,
                                              const std::function<double(std::size_t)>& u01);

// The same with the clusters' log masses already computed by
// ClusterLogMasses (the localizer needs them for HypothesesAlive first).
WeightedResample HypothesisPreservingResample(const std::vector<double>& normalized_log_weights,
                                              const HypothesisClusters& clusters,
                                              const std::vector<double>& cluster_log_masses, std::size_t output_count,
                                              const HypothesisFloor& floor,
                                              const std::function<double(std::size_t)>& u01);

}  // namespace rc
