#include "workloads/delibot/resampling.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

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

std::vector<std::size_t> SystematicResample(const std::vector<double>& normalized_log_weights, double u01,
                                            std::size_t output_count) {
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

namespace {

// A cluster of this log mass is alive: within window_nats of the heaviest.
bool WithinWindow(double log_mass, double heaviest, double window_nats) {
  return std::isfinite(log_mass) && log_mass >= heaviest - window_nats;
}

// Systematic pass over `members` (indices into log_weights, in this order),
// whose weights sum to exp(log_mass), writing `slots` ancestors.
void SystematicOver(const std::vector<double>& log_weights, const std::vector<std::size_t>& members, double log_mass,
                    std::size_t slots, double u01, std::vector<std::size_t>& out) {
  std::vector<double> local(members.size());
  for (std::size_t k = 0; k < members.size(); ++k) local[k] = log_weights[members[k]] - log_mass;
  for (std::size_t k : SystematicResample(local, u01, slots)) out.push_back(members[k]);
}

}  // namespace

std::vector<double> ClusterLogMasses(const std::vector<double>& normalized_log_weights,
                                     const HypothesisClusters& clusters) {
  if (clusters.cluster_of.size() != normalized_log_weights.size())
    throw std::invalid_argument("hypothesis clusters cover " + std::to_string(clusters.cluster_of.size()) +
                                " particles, the weights " + std::to_string(normalized_log_weights.size()));
  std::vector<double> log_mass(static_cast<std::size_t>(clusters.count), -std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < normalized_log_weights.size(); ++i) {
    double& m = log_mass[static_cast<std::size_t>(clusters.cluster_of[i])];
    m = LogAddExp(m, normalized_log_weights[i]);
  }
  return log_mass;
}

int HypothesesAlive(const std::vector<double>& cluster_log_masses, double window_nats) {
  if (cluster_log_masses.empty()) return 0;
  const double heaviest = *std::max_element(cluster_log_masses.begin(), cluster_log_masses.end());
  int alive = 0;
  for (double m : cluster_log_masses) alive += WithinWindow(m, heaviest, window_nats);
  return alive;
}

WeightedResample HypothesisPreservingResample(const std::vector<double>& normalized_log_weights,
                                              const HypothesisClusters& clusters, std::size_t output_count,
                                              const HypothesisFloor& floor,
                                              const std::function<double(std::size_t)>& u01) {
  // Throws if the clusters do not cover the weights, before they index anything.
  return HypothesisPreservingResample(normalized_log_weights, clusters,
                                      ClusterLogMasses(normalized_log_weights, clusters), output_count, floor, u01);
}

WeightedResample HypothesisPreservingResample(const std::vector<double>& normalized_log_weights,
                                              const HypothesisClusters& clusters, const std::vector<double>& log_mass,
                                              std::size_t output_count, const HypothesisFloor& floor,
                                              const std::function<double(std::size_t)>& u01) {
  const std::size_t n = normalized_log_weights.size();
  const std::size_t slots = output_count > 0 ? output_count : n;
  WeightedResample out;
  if (clusters.cluster_of.size() != n || log_mass.size() != static_cast<std::size_t>(clusters.count))
    throw std::invalid_argument("hypothesis clusters and their masses do not cover the weights");
  if (n == 0) return out;
  const auto k_count = static_cast<std::size_t>(clusters.count);
  std::vector<std::vector<std::size_t>> members(k_count);
  for (std::size_t i = 0; i < n; ++i) members[static_cast<std::size_t>(clusters.cluster_of[i])].push_back(i);
  // Eligible clusters, heaviest first (ties: lower index first).
  const double heaviest = *std::max_element(log_mass.begin(), log_mass.end());
  std::vector<std::size_t> eligible;
  if (floor.min_particles > 0)
    for (std::size_t c = 0; c < k_count; ++c)
      if (WithinWindow(log_mass[c], heaviest, floor.window_nats)) eligible.push_back(c);
  std::stable_sort(eligible.begin(), eligible.end(),
                   [&](std::size_t a, std::size_t b) { return log_mass[a] > log_mass[b]; });
  // Floor, one at a time, the heaviest eligible cluster whose proportional
  // share of the shared slots is below min_particles. Flooring one shrinks
  // every other share (the shared slots fall by m, the shared mass by less
  // than m / slots of the whole), so each flooring rescans from the
  // heaviest, until no share is below the floor or half the slots are
  // floored: the cap then goes to the heaviest hypotheses, not to whichever
  // light ones came first.
  const auto m = static_cast<std::size_t>(std::max(0, floor.min_particles));
  const std::size_t max_floored = m > 0 ? slots / (2 * m) : 0;
  std::vector<bool> floored(k_count, false);
  std::vector<std::size_t> floored_order;
  double free_mass = 1.0;
  while (floored_order.size() < max_floored) {
    const double shared_slots = static_cast<double>(slots - floored_order.size() * m);
    const auto below = std::find_if(eligible.begin(), eligible.end(), [&](std::size_t c) {
      return !floored[c] && shared_slots * std::exp(log_mass[c]) / free_mass < static_cast<double>(m);
    });
    if (below == eligible.end()) break;
    floored[*below] = true;
    floored_order.push_back(*below);
    free_mass -= std::exp(log_mass[*below]);
  }
  out.floored_clusters = static_cast<int>(floored_order.size());
  if (floored_order.empty()) {
    out.ancestors = SystematicResample(normalized_log_weights, u01(0), slots);
    out.log_weights.assign(slots, -std::log(static_cast<double>(slots)));
    out.shared_slots = slots;
    return out;
  }
  // The shared pass walks the other clusters one after another, so each of
  // them gets the floor or the ceiling of its share.
  std::vector<std::size_t> shared;
  for (std::size_t c = 0; c < k_count; ++c)
    if (!floored[c]) shared.insert(shared.end(), members[c].begin(), members[c].end());
  const std::size_t shared_slots = slots - floored_order.size() * m;
  out.shared_slots = shared_slots;
  out.ancestors.reserve(slots);
  out.log_weights.reserve(slots);
  // The shared mass, summed in the log domain (1 minus the floored masses
  // would round away tiny masses). A cluster is floored only while
  // its share is below min_particles, and the last cluster with mass outside
  // the floor has all the shared slots (at least half of them), so some mass
  // is always left to share.
  std::vector<double> shared_log_weights;
  shared_log_weights.reserve(shared.size());
  for (std::size_t i : shared) shared_log_weights.push_back(normalized_log_weights[i]);
  const double log_free_mass =
      shared.empty() ? -std::numeric_limits<double>::infinity() : LogSumExp(shared_log_weights);
  if (shared.empty() || !std::isfinite(log_free_mass))
    throw std::logic_error("hypothesis floor left no mass for the shared slots");
  SystematicOver(normalized_log_weights, shared, log_free_mass, shared_slots, u01(0), out.ancestors);
  out.log_weights.assign(shared_slots, log_free_mass - std::log(static_cast<double>(shared_slots)));
  for (std::size_t k = 0; k < floored_order.size(); ++k) {
    const std::size_t c = floored_order[k];
    SystematicOver(normalized_log_weights, members[c], log_mass[c], m, u01(k + 1), out.ancestors);
    out.log_weights.insert(out.log_weights.end(), m, log_mass[c] - std::log(static_cast<double>(m)));
  }
  // Rounding: renormalize so the weights sum to exactly 1 in the log domain.
  NormalizeLogWeights(out.log_weights);
  return out;
}

}  // namespace rc
