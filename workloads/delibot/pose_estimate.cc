#include "workloads/delibot/pose_estimate.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace rc {

namespace {

// Each particle's heading as a unit vector, computed once per estimate
// rather than once per mean-shift pass and seed.
struct HeadingVectors {
  std::vector<double> cos, sin;
};

// The weighted circular mean of headings (CircularMean's sums, the same
// operations in the same order) from precomputed unit vectors.
struct HeadingSum {
  double sum_cos = 0.0, sum_sin = 0.0;
  void Add(double c, double s, double weight) {
    sum_cos += weight * c;
    sum_sin += weight * s;
  }
  double Mean() const { return std::atan2(sum_sin, sum_cos); }
};

// Mean shift with a flat kernel from one start particle.
PoseEstimate ShiftToMode(const std::vector<Pose2>& particles, const std::vector<double>& w,
                         const HeadingVectors& headings, std::size_t start, double kernel_radius_m) {
  PoseEstimate out;
  double cx = particles[start].x, cy = particles[start].y;
  const double r2 = kernel_radius_m * kernel_radius_m;
  HeadingSum heading;
  double mode_weight = 0.0;
  constexpr int kMeanShiftIterations = 5;
  for (int it = 0; it < kMeanShiftIterations; ++it) {
    double sx = 0.0, sy = 0.0, sw = 0.0;
    HeadingSum h;
    for (std::size_t i = 0; i < particles.size(); ++i) {
      const double dx = particles[i].x - cx, dy = particles[i].y - cy;
      if (dx * dx + dy * dy > r2) continue;
      sx += w[i] * particles[i].x;
      sy += w[i] * particles[i].y;
      sw += w[i];
      h.Add(headings.cos[i], headings.sin[i], w[i]);
    }
    if (sw <= 0.0) break;
    const double nx = sx / sw, ny = sy / sw;
    const bool settled = std::hypot(nx - cx, ny - cy) < 1e-6;
    cx = nx;
    cy = ny;
    heading = h;
    mode_weight = sw;
    if (settled) break;
  }
  out.pose = {cx, cy, mode_weight > 0.0 ? heading.Mean() : particles[start].theta};
  out.mode_weight = mode_weight;
  return out;
}

// How many of the heaviest particles seed a mean-shift search. One seed is
// not enough: right after random particles are injected, a lone stray
// particle can outweigh every single member of the true, populous mode.
constexpr std::size_t kModeSeeds = 16;

}  // namespace

PoseEstimate EstimatePose(const std::vector<Pose2>& particles, const std::vector<double>& normalized_log_weights,
                          double kernel_radius_m) {
  PoseEstimate out;
  if (particles.empty()) return out;
  // The per-particle work and the seeds' searches run in parallel: each
  // value is computed alone, and the sums and the choice of the best seed
  // below keep their serial order, so the estimate does not depend on the
  // thread count.
  const long n = static_cast<long>(particles.size());
  std::vector<double> w(particles.size());
  HeadingVectors headings;
  headings.cos.resize(particles.size());
  headings.sin.resize(particles.size());
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; ++i) {
    w[i] = std::exp(normalized_log_weights[i]);
    headings.cos[i] = std::cos(particles[i].theta);
    headings.sin[i] = std::sin(particles[i].theta);
  }
  std::vector<std::size_t> order(particles.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  const std::size_t seeds = std::min(kModeSeeds, order.size());
  // Heaviest first; ties broken by index so the result is deterministic.
  std::partial_sort(order.begin(), order.begin() + seeds, order.end(),
                    [&](std::size_t a, std::size_t b) { return w[a] != w[b] ? w[a] > w[b] : a < b; });
  // Seeds that start from the same pose (copies made by resampling) give
  // the same search: each is run once. A search is a function of its start
  // pose alone (with the weights and particles), and a copy can never
  // replace the first of its kind below (equal, not greater, weight).
  std::vector<long> first_of_kind(seeds);
  for (std::size_t k = 0; k < seeds; ++k) {
    first_of_kind[k] = static_cast<long>(k);
    const Pose2& p = particles[order[k]];
    for (std::size_t j = 0; j < k; ++j) {
      const Pose2& q = particles[order[j]];
      if (std::memcmp(&p, &q, sizeof(Pose2)) == 0) {
        first_of_kind[k] = static_cast<long>(j);
        break;
      }
    }
  }
  std::vector<PoseEstimate> candidates(seeds);
#pragma omp parallel for schedule(dynamic, 1)
  for (long k = 0; k < static_cast<long>(seeds); ++k)
    if (first_of_kind[k] == k) candidates[k] = ShiftToMode(particles, w, headings, order[k], kernel_radius_m);
  for (std::size_t k = 0; k < seeds; ++k) candidates[k] = candidates[first_of_kind[k]];
  out.mode_weight = -1.0;
  for (const PoseEstimate& candidate : candidates)
    if (candidate.mode_weight > out.mode_weight + 1e-12) out = candidate;
  const double cx = out.pose.x, cy = out.pose.y;
  double spread = 0.0;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const double dx = particles[i].x - cx, dy = particles[i].y - cy;
    spread += w[i] * (dx * dx + dy * dy);
  }
  out.spread_m = std::sqrt(spread);
  return out;
}

}  // namespace rc
