#include "workloads/delibot/monte_carlo_localizer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "common/log_domain.h"
#include "common/pose_algebra.h"
#include "common/random_stream.h"
#include "workloads/delibot/motion_model.h"
#include "workloads/delibot/resampling.h"

namespace rc {

MonteCarloLocalizer::MonteCarloLocalizer(const OccupancyGrid& grid, std::unique_ptr<SensorModel> sensor_model,
                                         MclOptions options)
    : grid_(grid), sensor_model_(std::move(sensor_model)), options_(options) {
  std::string error;
  if (!options_.IsValid(&error)) throw std::invalid_argument(error);
  free_cells_ = grid_.FreeCellIndices();
  work_.record_kernel = options_.record_kernel;
  check_work_.record_kernel = options_.record_kernel;
  work_.record_sample = check_work_.record_sample = options_.record_sample;
  work_.record_choices = check_work_.record_choices = options_.record_choices;
  work_.price_launch = options_.price_launch;
  work_.launch_sample = options_.launch_sample;
  work_.estimate_launches = options_.estimate_launches;
  if (free_cells_.empty()) throw std::invalid_argument("the map has no free cell: there is nowhere to localize");
}

Pose2 MonteCarloLocalizer::RandomFreePose(RandomStream& stream) const {
  const std::uint32_t cell = free_cells_[stream.Below(free_cells_.size())];
  const int ix = static_cast<int>(cell / static_cast<std::uint32_t>(grid_.size_y()));
  const int iy = static_cast<int>(cell % static_cast<std::uint32_t>(grid_.size_y()));
  const double r = grid_.resolution_m();
  return {(ix + stream.Uniform()) * r, (iy + stream.Uniform()) * r, stream.Uniform(-kPi, kPi)};
}

Pose2 MonteCarloLocalizer::PoseAround(RandomStream& stream) const {
  constexpr int kMaxTries = 1000;
  const InitialSpread& a = initial_;
  Pose2 p = a.pose;
  for (int attempt = 0; attempt < kMaxTries; ++attempt) {
    p = {a.pose.x + stream.Gaussian(a.sigma_xy_m), a.pose.y + stream.Gaussian(a.sigma_xy_m),
         WrapAngle(a.pose.theta + stream.Gaussian(a.sigma_theta_rad))};
    if (grid_.IsFreePoint(p.x, p.y)) break;
  }
  return p;
}

Pose2 MonteCarloLocalizer::DrawInitialPose(RandomStream& stream) const {
  return initial_.around ? PoseAround(stream) : RandomFreePose(stream);
}

void MonteCarloLocalizer::InitializeUniform() {
  initial_ = InitialSpread{};
  const double cell_area_m2 = grid_.resolution_m() * grid_.resolution_m();
  const std::size_t n = InitialParticleCount(options_, static_cast<double>(free_cells_.size()) * cell_area_m2);
  particles_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    RandomStream stream(options_.seed, StreamPurpose::kInitialization, 0, i);
    particles_[i] = RandomFreePose(stream);
  }
  log_weights_.assign(n, -std::log(static_cast<double>(n)));
  dense_initial_set_ = n > static_cast<std::size_t>(options_.particle_count);
}

void MonteCarloLocalizer::InitializeAround(const Pose2& pose, double sigma_xy_m, double sigma_theta_rad) {
  initial_ = InitialSpread{true, pose, sigma_xy_m, sigma_theta_rad};
  const auto n = static_cast<std::size_t>(options_.particle_count);
  particles_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    RandomStream stream(options_.seed, StreamPurpose::kInitialization, 0, i);
    particles_[i] = PoseAround(stream);
  }
  log_weights_.assign(n, -std::log(static_cast<double>(n)));
  dense_initial_set_ = false;
  // One hypothesis by construction: a staged model tracks from the start.
  sensor_model_->BeginTracking();
}

MclStepResult MonteCarloLocalizer::Update(const LaserScan& scan, const LaserGeometry& geometry,
                                          std::uint64_t iteration) {
  if (particles_.empty()) throw std::logic_error("MonteCarloLocalizer::Update before initialization");
  MclStepResult result;
  result.tracking = sensor_model_->Tracking();
  check_records_.clear();
  result.check_records = &check_records_;
  if (have_odometry_) {
    const OdometryDelta delta = ComputeOdometryDelta(last_odometry_, scan.odometry);
    if (!delta.IsZero()) {
      const long n = static_cast<long>(particles_.size());
#pragma omp parallel for schedule(static)
      for (long i = 0; i < n; ++i) {
        RandomStream stream(options_.seed, StreamPurpose::kMotion, iteration, static_cast<std::uint64_t>(i));
        particles_[i] = SampleOdometryMotion(particles_[i], delta, options_.motion, stream);
      }
    }
    moved_d_m_ += delta.trans;
    moved_a_rad_ += std::abs(delta.rot1) + std::abs(delta.rot2);
  }
  last_odometry_ = scan.odometry;
  have_odometry_ = true;

  const bool moved_enough = moved_d_m_ >= options_.update_min_d_m || moved_a_rad_ >= options_.update_min_a_rad;
  if (first_sensor_update_done_ && !moved_enough) {
    result.ess = EffectiveSampleSize(log_weights_);
    return result;
  }
  first_sensor_update_done_ = true;
  moved_d_m_ = moved_a_rad_ = 0.0;

  if (dense_initial_set_)
    sensor_model_->SelectionLogLikelihoods(particles_, scan, geometry, options_.beams, log_likelihoods_, work_);
  else
    sensor_model_->LogLikelihoods(particles_, scan, geometry, options_.beams, log_likelihoods_, work_);
  if (options_.reject_poses_in_obstacles) RejectPosesInObstacles(log_likelihoods_);
  for (std::size_t i = 0; i < particles_.size(); ++i) log_weights_[i] += log_likelihoods_[i];
  // With normalized prior weights, the normalizer is the weighted mean
  // likelihood of the scan: augmented MCL's w_avg, kept in the log domain.
  const double log_w_avg = NormalizeLogWeights(log_weights_);
  result.log_mean_likelihood = log_w_avg;
  result.sensor_updated = true;
  result.work = &work_;
  if (options_.alpha_slow > 0.0) {
    // The recovery averages track the per-beam geometric mean of the scan
    // likelihood, exp(log w_avg / beams). The whole-scan likelihood is a
    // product over beams, so it swings by e^20 and more between ordinary
    // scans (more or fewer max readings, people in view); a linear average
    // of it is ruled by the best scan ever seen, every later scan looks like
    // a kidnap, and injection runs away. AMCL avoids this only because its
    // beam "likelihood" is a sum of cubes, not a product.
    const double beams = std::max(1, work_.beams_scored);
    const double log_w_beam = log_w_avg / beams;
    if (!have_recovery_averages_) {
      log_w_slow_ = log_w_fast_ = log_w_beam;
      have_recovery_averages_ = true;
    } else {
      // w += alpha * (w_avg - w), i.e. w = (1 - alpha) w + alpha w_avg.
      log_w_slow_ =
          LogAddExp(std::log1p(-options_.alpha_slow) + log_w_slow_, std::log(options_.alpha_slow) + log_w_beam);
      log_w_fast_ =
          LogAddExp(std::log1p(-options_.alpha_fast) + log_w_fast_, std::log(options_.alpha_fast) + log_w_beam);
    }
    result.injection_probability = std::max(0.0, 1.0 - std::exp(log_w_fast_ - log_w_slow_));
  }
  const auto remembered =
      static_cast<std::size_t>(std::max(options_.injection_check_updates, options_.claim_audit_scans));
  if (remembered > 0) {
    recent_scans_.push_back({scan, geometry});
    while (recent_scans_.size() > remembered) recent_scans_.pop_front();
  }
  result.ess = EffectiveSampleSize(log_weights_);
  // The dense first set is not clustered: spread uniformly over the map it
  // is one connected cluster, and its point is to let the scan pick the few
  // places worth keeping, which plain systematic resampling does.
  std::optional<HypothesisClusters> clusters;
  std::vector<double> cluster_log_masses;
  // A staged model needs the count of hypotheses alive to hand over, floor
  // or not (without a floor the resampling below stays plain).
  if ((options_.hypothesis_floor.min_particles > 0 || sensor_model_->HasTrackingStage()) && !dense_initial_set_) {
    clusters = ClusterHypotheses(particles_, options_.estimate_kernel_radius_m, options_.hypothesis_heading_bins);
    cluster_log_masses = ClusterLogMasses(log_weights_, *clusters);
    result.hypotheses_alive = HypothesesAlive(cluster_log_masses, options_.hypothesis_floor.window_nats);
  }
  // A staged model hands over to its tracking model once one hypothesis has
  // been alive for tracking_after_single_updates updates in a row; the set,
  // grown for rivals, is cut to particle_count by a plain resampling then
  // (one hypothesis: the floor would change nothing).
  bool begin_tracking = false;
  if (sensor_model_->HasTrackingStage() && !sensor_model_->Tracking() && clusters) {
    single_hypothesis_updates_ = result.hypotheses_alive == 1 ? single_hypothesis_updates_ + 1 : 0;
    begin_tracking = single_hypothesis_updates_ >= options_.tracking_after_single_updates;
  }
  if (begin_tracking) {
    Resample(iteration, nullptr, cluster_log_masses, result);
    sensor_model_->BeginTracking();
    result.began_tracking = true;
  } else if (dense_initial_set_ ||
             result.ess < options_.resample_ess_fraction * static_cast<double>(particles_.size())) {
    Resample(iteration, clusters ? &*clusters : nullptr, cluster_log_masses, result);
  }
  return result;
}

void MonteCarloLocalizer::RejectPosesInObstacles(std::vector<double>& log_likelihoods) const {
  const double r = grid_.resolution_m();
  auto inside_obstacle = [&](const Pose2& p) {
    const int ix = static_cast<int>(std::floor(p.x / r));
    const int iy = static_cast<int>(std::floor(p.y / r));
    return !grid_.IsFree(ix, iy);
  };
  std::size_t rejected = 0;
  for (const Pose2& p : particles_) rejected += inside_obstacle(p) ? 1 : 0;
  // If every particle is inside an obstacle, zero weights everywhere would
  // leave nothing to normalize; the scan alone then decides.
  if (rejected == 0 || rejected == particles_.size()) return;
  for (std::size_t i = 0; i < particles_.size(); ++i)
    if (inside_obstacle(particles_[i])) log_likelihoods[i] = -std::numeric_limits<double>::infinity();
}

std::size_t MonteCarloLocalizer::ResampledSetSize(int hypotheses_alive) const {
  const auto base = static_cast<std::size_t>(options_.particle_count);
  if (options_.max_particle_count == 0) return base;
  // The dense first set is not clustered (Update), so how many places
  // deserve particles is not known yet: keep as many as allowed, and let the
  // next update's clusters decide.
  if (dense_initial_set_) return static_cast<std::size_t>(options_.max_particle_count);
  if (hypotheses_alive <= 1) return base;
  // Twice the floors of all live hypotheses: HypothesisPreservingResample
  // floors at most half of the slots.
  const std::size_t wanted = 2 * static_cast<std::size_t>(hypotheses_alive) *
                             static_cast<std::size_t>(options_.hypothesis_floor.min_particles);
  return std::clamp(wanted, base, static_cast<std::size_t>(options_.max_particle_count));
}

void MonteCarloLocalizer::Resample(std::uint64_t iteration, const HypothesisClusters* clusters,
                                   const std::vector<double>& cluster_log_masses, MclStepResult& result) {
  const std::size_t slots = ResampledSetSize(result.hypotheses_alive);
  auto pass_offset = [&](std::size_t pass) {
    return RandomStream(options_.seed, StreamPurpose::kResample, iteration, pass).Uniform();
  };
  std::vector<std::size_t> ancestors;
  std::vector<double> next_log_weights;
  // Random poses replace only equal-weight slots: one put in a floored
  // hypothesis's slot would inherit that hypothesis's tiny weight (useless
  // from the start) and push the hypothesis below its floor.
  std::size_t injectable_slots = slots;
  if (clusters) {
    WeightedResample resampled = HypothesisPreservingResample(log_weights_, *clusters, cluster_log_masses, slots,
                                                              options_.hypothesis_floor, pass_offset);
    ancestors = std::move(resampled.ancestors);
    next_log_weights = std::move(resampled.log_weights);
    injectable_slots = resampled.shared_slots;
  } else {
    ancestors = SystematicResample(log_weights_, pass_offset(0), slots);
    next_log_weights.assign(slots, -std::log(static_cast<double>(slots)));
  }
  std::vector<Pose2> next(ancestors.size());
  // Draw the random poses first (each slot keeps its own stream, so the
  // draws do not depend on the check), then admit those that pass it.
  std::vector<std::size_t> candidate_slots;
  std::vector<Pose2> candidates;
  for (std::size_t slot = 0; slot < next.size(); ++slot) {
    next[slot] = particles_[ancestors[slot]];
    if (result.injection_probability > 0.0 && slot < injectable_slots) {
      RandomStream stream(options_.seed, StreamPurpose::kInjection, iteration, slot);
      if (stream.Uniform() < result.injection_probability) {
        candidate_slots.push_back(slot);
        candidates.push_back(RandomFreePose(stream));
      }
    }
  }
  std::vector<bool> admitted(candidates.size(), true);
  if (options_.injection_check_updates > 0 && !candidates.empty()) {
    // Each random pose must beat the particle it would replace, scored on
    // the same scans. Not the estimate: a random pose is never as finely
    // placed as a refined estimate, so after a wrong global convergence no
    // random pose near the truth would pass, while a particle of the wrong
    // cloud is beaten by one that is merely near the truth.
    const std::size_t m = candidates.size();
    std::vector<Pose2> poses = candidates;
    for (std::size_t k = 0; k < m; ++k) poses.push_back(next[candidate_slots[k]]);
    const std::vector<double> scores = RecentScansLogLikelihood(poses, result);
    for (std::size_t k = 0; k < m; ++k) admitted[k] = scores[k] > scores[m + k];
  }
  int injected = 0;
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    if (!admitted[k]) {
      ++result.injection_rejected;
      continue;
    }
    next[candidate_slots[k]] = candidates[k];
    ++injected;
  }
  particles_.swap(next);
  dense_initial_set_ = false;
  // An injected particle takes the (equal) weight of the shared slot it
  // replaces.
  log_weights_.swap(next_log_weights);
  result.resampled = true;
  result.injected = injected;
  // AMCL resets both averages after an injection; then a kidnap injects
  // one small batch, the averages restart at the new low level, and the
  // few random particles rarely land near the truth. We keep Thrun's
  // original rule: injection continues until the short-term average
  // likelihood has recovered.
}

std::vector<double> MonteCarloLocalizer::RecentScansLogLikelihood(const std::vector<Pose2>& poses_now,
                                                                  MclStepResult& result) {
  std::vector<double> total(poses_now.size(), 0.0);
  if (recent_scans_.empty()) return total;
  const Pose2& odometry_now = recent_scans_.back().scan.odometry;
  std::vector<Pose2> poses_then(poses_now.size());
  std::vector<double> log_likelihoods;
  const std::size_t checked =
      std::min(recent_scans_.size(), static_cast<std::size_t>(options_.injection_check_updates));
  for (auto it = recent_scans_.end() - static_cast<std::ptrdiff_t>(checked); it != recent_scans_.end(); ++it) {
    const RememberedScan& remembered = *it;
    // Where each pose was at that scan if the odometry since then is right.
    const Pose2 back = Between(odometry_now, remembered.scan.odometry);
    for (std::size_t i = 0; i < poses_now.size(); ++i) poses_then[i] = Compose(poses_now[i], back);
    sensor_model_->LogLikelihoods(poses_then, remembered.scan, remembered.geometry, options_.beams, log_likelihoods,
                                  check_work_);
    for (std::size_t i = 0; i < poses_now.size(); ++i) total[i] += log_likelihoods[i];
    // These casts run on the same device as the update's, so they are
    // priced with it: one launch per replayed scan.
    result.check_rays += check_work_.rays;
    result.check_nodes += check_work_.nodes;
    if (check_work_.record_kernel) {
      check_records_.push_back(std::move(check_work_.record));
      check_work_.record = KernelRecord{};
    }
  }
  return total;
}

ClaimAudit MonteCarloLocalizer::AuditClaim(const Pose2& claimed, std::uint64_t iteration) {
  if (options_.claim_audit_scans <= 0) throw std::logic_error("AuditClaim with claim audits off");
  if (recent_scans_.empty()) throw std::logic_error("AuditClaim before the first sensor update");
  std::deque<RememberedScan> audited(
      recent_scans_.end() - static_cast<std::ptrdiff_t>(
                                std::min(recent_scans_.size(), static_cast<std::size_t>(options_.claim_audit_scans))),
      recent_scans_.end());
  auto draw_poses = [&] {
    MclOptions sizing = options_;
    sizing.initial_particle_count = kAutoInitialParticles;
    const double cell_area_m2 = grid_.resolution_m() * grid_.resolution_m();
    const std::size_t n = InitialParticleCount(sizing, static_cast<double>(free_cells_.size()) * cell_area_m2);
    std::vector<Pose2> poses(n);
    const long count = static_cast<long>(n);
#pragma omp parallel for schedule(static)
    for (long i = 0; i < count; ++i) {
      RandomStream stream(options_.seed, StreamPurpose::kClaimAudit, iteration, static_cast<std::uint64_t>(i));
      poses[i] = RandomFreePose(stream);
    }
    return poses;
  };
  const ClaimedPlace place{claimed, options_.estimate_kernel_radius_m, 2.0 * kPi / options_.hypothesis_heading_bins};
  return rc::AuditClaim(sensor_model_->PlaceModel(), grid_, audited, options_.beams, draw_poses, place,
                        options_.hypothesis_floor.window_nats, audit_rivals_);
}

PoseEstimate MonteCarloLocalizer::Estimate() const {
  return EstimatePose(particles_, log_weights_, options_.estimate_kernel_radius_m);
}

}  // namespace rc
