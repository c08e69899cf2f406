#pragma once
// Tunables of the Monte Carlo localizer, with units and ranges. Defaults are
// nav2 AMCL's where it has one (REFERENCE.md section 4), otherwise stated.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

#include "workloads/delibot/motion_model.h"
#include "workloads/delibot/resampling.h"
#include "workloads/delibot/sensor_model.h"

namespace rc {

struct MclOptions {
  int particle_count = 2000;  // [1, 10^7]
  // Global localization starts from this many uniform particles (0: the
  // particle count) and the first sensor update resamples them down to
  // particle_count. Why: some particle must start within the sensor model's
  // reach of the true pose (~0.2 m, ~5 deg), or the filter locks onto
  // whichever look-alike the first scans favour (docs/real_logs.md, "A dense
  // first set"). kAutoInitialParticles sizes the set by the map
  // (InitialParticleCount).
  int initial_particle_count = 0;  // kAutoInitialParticles, 0, or [particle_count, 10^7]
  std::uint64_t seed = 1;
  OdometryMotionNoise motion;
  BeamSelection beams{6};  // every 6th beam: 30 of 180 (nav2 uses 60); [1, beam count]
  // A particle whose robot centre is not in a free cell (occupied, unknown,
  // or off the map) gets zero weight: the same free space that global
  // localization samples from. The likelihood field needs this most: it
  // scores only beam endpoints, so a particle inside a thick wall sees every
  // endpoint land "on an obstacle" and outscores the true pose
  // (docs/real_logs.md, "Free space").
  bool reject_poses_in_obstacles = true;
  double resample_ess_fraction = 0.5;  // resample when ESS < fraction * N; (0, 1]
  // Hypothesis-preserving resampling (resampling.h): a cluster of particles
  // (clusters: hypothesis_clusters.h, bins of estimate_kernel_radius_m and
  // 360 / hypothesis_heading_bins deg) whose posterior mass is within
  // window_nats of the heaviest keeps at least min_particles particles,
  // weighted so the belief is unchanged. min_particles 0 = plain systematic
  // resampling (the default). While a second hypothesis is alive the filter
  // does not claim convergence without ground truth (delibot_run.h).
  // min_particles should be hundreds: a hypothesis held by few particles
  // loses evidence to sampling (docs/real_logs_particles.md). The window is
  // in the nats of the scan likelihood, so it scales with the beam
  // combination: the default 200 nats suits the product; under the cube sum
  // (BeamCombination::kAmclCubeSum) the evidence between places is tens of
  // nats, and the window must shrink with it (docs/real_logs_window.md).
  HypothesisFloor hypothesis_floor{0, 200.0};  // [0, particle_count / 2] particles, [0, 10^4] nats
  // With a floor, the set grows while rivals are alive so that each keeps
  // its floor: a resampling draws max(particle_count, 2 * alive * floor)
  // particles, at most this many (the floor takes at most half the slots).
  // At a fixed size the floor holds only particle_count / (2 * floor)
  // hypotheses and may drop the true one for good
  // (docs/real_logs_particles.md). The set shrinks back as the rivals fall
  // out of the window, as KLD sampling (Fox 2003; AMCL's max_particles)
  // sizes the set by the support of the belief. 0 = fixed size (the
  // default). [0 or particle_count, 10^7].
  int max_particle_count = 0;
  int hypothesis_heading_bins = 12;  // 30 deg heading bins; [1, 360]
  // Augmented MCL (Probabilistic Robotics, Table 8.3): random particles are
  // injected when the short-term average likelihood falls below the
  // long-term one. alpha_slow < alpha_fast; both 0 disables injection.
  double alpha_slow = 0.001;  // nav2's suggested recovery_alpha_slow
  double alpha_fast = 0.1;    // nav2's suggested recovery_alpha_fast
  // Checked injection (0 = augmented MCL as published). A random pose
  // replaces a particle only if it explains the scans of the last this-many
  // sensor updates better than that particle does, both replayed back
  // through the odometry. Why: published augmented MCL lets a random pose
  // win on one scan (a person blocking the beams for a moment), while a
  // look-alike rarely fits several scans along the driven path; after a
  // real kidnap recovery is delayed by the window, not lost. 10 updates at
  // the 5 cm update distance span about 0.5 m of driving. Off by default
  // because it also slows the escape from a wrong global convergence
  // (docs/delibot.md, "Checked injection"). [0, 1000] sensor updates.
  int injection_check_updates = 0;
  // Claim audit (claim_audit.h): the localizer remembers this many recent
  // sensor updates' scans so that a claim can be audited on them
  // (AuditClaim); 0 = off (the default). RunDelibot sets it from
  // DelibotSettings::claim_audit_scans when it audits claims
  // (delibot_run.h). [0, 1000] sensor updates.
  int claim_audit_scans = 0;
  // A sensor update runs only after the odometry has moved this far since
  // the previous one (AMCL's update_min_d / update_min_a); 0 = every scan.
  // Repeated updates with the same scan while standing still make the filter
  // overconfident and starve it of diversity.
  double update_min_d_m = 0.05;
  double update_min_a_rad = 0.05;
  double estimate_kernel_radius_m = 1.0;  // mean-shift radius of the point estimate
  // With a sensor model that has a tracking stage (staged_sensor_model.h)
  // and a hypothesis floor: the tracking model takes over after this many
  // consecutive sensor updates with one hypothesis alive, the count after
  // which the summary lets the filter claim convergence (delibot_summary.cc,
  // kSustainRecords), and the set is cut to particle_count then. Tracking
  // from a known pose (InitializeAround) starts in the tracking stage.
  // [1, 1000] sensor updates.
  int tracking_after_single_updates = 10;
  // Record every ray's node fetches (robocore/kernel_record.h) so that the
  // backends can price the update; off, the kernel runs without the hook.
  bool record_kernel = false;
  AddressSample record_sample;      // whose node addresses the record keeps (default: all)
  RayKernelChoices record_choices;  // how the recorded kernel stores the grid and which march program it prices
  // Prices each launch of an update split by kMaxRaysPerLaunch but the last
  // (SensorUpdateWork::price_launch); unset: updates are not split.
  std::function<void(const KernelRecord&)> price_launch;
  // Which of those launches are recorded, and where the others go
  // (SensorUpdateWork::launch_sample, estimate_launches).
  LaunchSample launch_sample;
  std::function<void(const EstimatedLaunches&)> estimate_launches;

  bool IsValid(std::string* error) const;
};

// initial_particle_count that sizes the dense first set of global
// localization by the map's free space: enough uniform particles that, on
// average, kAutoInitialNearPose of them start within kAutoInitialNearXyM
// and kAutoInitialNearThetaRad of any pose (Poisson: none with probability
// e^-4, 2 %). The first update can only keep a place some particle
// starts near; 500,000 particles on Wean Hall's 483 m^2 of free space
// leave about one there, and lost the true place in one of ten seeds
// (docs/defaults.md). 0.15 m and 3 deg is the reach measured there.
constexpr int kAutoInitialParticles = -1;
constexpr double kAutoInitialNearPose = 4.0;                                       // expected particles [count]
constexpr double kAutoInitialNearXyM = 0.15;                                       // radius [m]
constexpr double kAutoInitialNearThetaRad = 3.0 * 3.14159265358979323846 / 180.0;  // half-width [rad]
// The auto size is capped (memory: about 100 bytes per particle while the
// dense set is scored and resampled, so 4e6 take 0.4 GB).
constexpr int kAutoInitialParticlesCap = 4000000;  // [count]

// The particles InitializeUniform draws: particle_count, the explicit
// initial_particle_count, or the auto size for free_area_m2 of free space
// (at least particle_count, at most kAutoInitialParticlesCap).
std::size_t InitialParticleCount(const MclOptions& options, double free_area_m2);

}  // namespace rc
