#include "workloads/delibot/pose_estimate.h"

#include <cmath>

namespace rc {

PoseEstimate EstimatePose(const std::vector<Pose2>& particles,
                          const std::vector<double>& normalized_log_weights, double kernel_radius_m) {
  PoseEstimate out;
  if (particles.empty()) return out;
  std::vector<double> w(particles.size());
  std::size_t best = 0;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    w[i] = std::exp(normalized_log_weights[i]);
    if (w[i] > w[best]) best = i;
  }
  double cx = particles[best].x, cy = particles[best].y;
  const double r2 = kernel_radius_m * kernel_radius_m;
  CircularMean heading;
  double mode_weight = 0.0;
  constexpr int kMeanShiftIterations = 5;
  for (int it = 0; it < kMeanShiftIterations; ++it) {
    double sx = 0.0, sy = 0.0, sw = 0.0;
    CircularMean h;
    for (std::size_t i = 0; i < particles.size(); ++i) {
      const double dx = particles[i].x - cx, dy = particles[i].y - cy;
      if (dx * dx + dy * dy > r2) continue;
      sx += w[i] * particles[i].x;
      sy += w[i] * particles[i].y;
      sw += w[i];
      h.Add(particles[i].theta, w[i]);
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
  out.pose = {cx, cy, mode_weight > 0.0 ? heading.Mean() : particles[best].theta};
  out.mode_weight = mode_weight;
  double spread = 0.0;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const double dx = particles[i].x - cx, dy = particles[i].y - cy;
    spread += w[i] * (dx * dx + dy * dy);
  }
  out.spread_m = std::sqrt(spread);
  return out;
}

}  // namespace rc
