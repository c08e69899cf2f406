#pragma once
// Monte Carlo Localization with log-domain weights, per-particle random
// streams, systematic resampling on low ESS, and augmented-MCL recovery.
// Parallel over particles (OpenMP); every random draw comes from a stream
// keyed by (seed, purpose, iteration, particle), so the result is identical
// at any thread count.
#include <cstdint>
#include <deque>
#include <memory>
#include <vector>

#include "maps/occupancy_grid.h"
#include "workloads/delibot/claim_audit.h"
#include "workloads/delibot/hypothesis_clusters.h"
#include "workloads/delibot/mcl_options.h"
#include "workloads/delibot/pose_estimate.h"
#include "workloads/delibot/sensor_model.h"

namespace rc {

struct MclStepResult {
  bool sensor_updated = false;
  bool resampled = false;
  int injected = 0;            // particles replaced by random free-space poses
  int injection_rejected = 0;  // random poses drawn but refused by the injection check
  // With the hypothesis floor: hypotheses within its window after this
  // update (1 = no rival; hypothesis_clusters.h). 0 when not computed (floor
  // off, no sensor update, or the dense first update).
  int hypotheses_alive = 0;
  double ess = 0.0;  // effective sample size after the update, before resampling
  // A staged sensor model (staged_sensor_model.h): whether its tracking
  // model scored this record (held, when no update ran), and whether this
  // update handed over to it for the records that follow.
  bool tracking = false;
  bool began_tracking = false;
  double log_mean_likelihood = 0.0;  // log of the weighted mean scan likelihood
  double injection_probability = 0.0;
  const SensorUpdateWork* work = nullptr;  // valid until the next Update()
  // The injection check's work this record: its queries and node fetches,
  // and with record_kernel one kernel record per replayed scan (each a
  // launch of the same kernel), valid until the next Update().
  std::uint64_t check_rays = 0;
  std::uint64_t check_nodes = 0;
  const std::vector<KernelRecord>* check_records = nullptr;
};

class MonteCarloLocalizer {
 public:
  // Throws std::invalid_argument for invalid options or a grid with no free
  // cell (global localization has nowhere to put a particle).
  MonteCarloLocalizer(const OccupancyGrid& grid, std::unique_ptr<SensorModel> sensor_model, MclOptions options);

  // Global localization: particles uniform over free cells, headings uniform.
  void InitializeUniform();
  // Tracking: particles around a known pose, rejecting non-free positions.
  void InitializeAround(const Pose2& pose, double sigma_xy_m, double sigma_theta_rad);
  // One pose drawn from `stream` as the last Initialize* drew each particle
  // (uniform over free space, or around the tracking start): what the first
  // update's particles look like before it runs, for a caller that must not
  // see them (the scheduler's start probe, start_probe.h).
  Pose2 DrawInitialPose(RandomStream& stream) const;

  // Processes one laser record (its odometry pose and ranges). `iteration`
  // keys the random streams and must increase by one per record.
  MclStepResult Update(const LaserScan& scan, const LaserGeometry& geometry, std::uint64_t iteration);

  PoseEstimate Estimate() const;
  // Audits a claim that the robot is at `claimed` (claim_audit.h) on the
  // last claim_audit_scans sensor updates' scans (fewer if fewer ran),
  // sampling free space with the auto-sized dense first set's count of
  // uniform poses (streams keyed by `iteration`); the claimed place is the
  // poses within the hypothesis clusters' bin sizes of `claimed`
  // (estimate_kernel_radius_m, 360 / hypothesis_heading_bins deg) and the
  // margin the hypothesis floor's window; a refused audit's rivals are
  // re-checked first by the next. Throws std::logic_error
  // when claim audits are off or before the first sensor update.
  ClaimAudit AuditClaim(const Pose2& claimed, std::uint64_t iteration);
  const std::vector<Pose2>& particles() const { return particles_; }
  const std::vector<double>& log_weights() const { return log_weights_; }
  const MclOptions& options() const { return options_; }
  const SensorModel& sensor_model() const { return *sensor_model_; }

 private:
  Pose2 RandomFreePose(RandomStream& stream) const;
  // A free pose around `around` (InitializeAround), or the last draw after
  // kMaxTries non-free ones.
  Pose2 PoseAround(RandomStream& stream) const;
  // clusters: the hypotheses of the current particles, with their log
  // masses (ClusterLogMasses), or null to resample plainly.
  void Resample(std::uint64_t iteration, const HypothesisClusters* clusters,
                const std::vector<double>& cluster_log_masses, MclStepResult& result);
  // Particles a resampling draws: particle_count, or more while rivals are
  // alive (MclOptions::max_particle_count).
  std::size_t ResampledSetSize(int hypotheses_alive) const;
  // Log-likelihood of each pose (a pose now) over the remembered scans, each
  // scored at the pose replayed back through the odometry since that scan.
  // Adds the casts' work (and kernel records) to `result`.
  std::vector<double> RecentScansLogLikelihood(const std::vector<Pose2>& poses_now, MclStepResult& result);
  // Sets -inf for particles outside free space (see MclOptions).
  void RejectPosesInObstacles(std::vector<double>& log_likelihoods) const;

  const OccupancyGrid& grid_;
  std::unique_ptr<SensorModel> sensor_model_;
  MclOptions options_;
  std::vector<std::uint32_t> free_cells_;
  std::vector<Pose2> particles_;
  // The initial distribution: uniform over free space, or around a pose.
  struct InitialSpread {
    bool around = false;
    Pose2 pose;
    double sigma_xy_m = 0.0, sigma_theta_rad = 0.0;
  } initial_;
  std::vector<double> log_weights_;      // normalized: sum of exp == 1
  std::vector<double> log_likelihoods_;  // scratch
  SensorUpdateWork work_;
  bool have_odometry_ = false;
  Pose2 last_odometry_;
  double moved_d_m_ = 0.0, moved_a_rad_ = 0.0;  // since the last sensor update
  bool first_sensor_update_done_ = false;
  // The uniform set of global localization, larger than particle_count,
  // before its first resampling (it is scored and resampled differently).
  bool dense_initial_set_ = false;
  bool have_recovery_averages_ = false;
  int single_hypothesis_updates_ = 0;  // consecutive sensor updates with one hypothesis alive
  double log_w_slow_ = 0.0, log_w_fast_ = 0.0;
  // The last max(injection_check_updates, claim_audit_scans) sensor
  // updates' scans, oldest first.
  std::deque<RememberedScan> recent_scans_;
  RememberedRivals audit_rivals_;            // the last refused claim audit's rivals
  SensorUpdateWork check_work_;              // scratch for the injection check's casts
  std::vector<KernelRecord> check_records_;  // this record's, when record_kernel
};

}  // namespace rc
