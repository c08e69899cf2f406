#include "workloads/delibot/mrpt/mrpt_localizer.h"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include <mrpt/bayes/CParticleFilter.h>
#include <mrpt/maps/COccupancyGridMap2D.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/random/RandomGenerators.h>
#include <mrpt/slam/CMonteCarloLocalization2D.h>

#include "common/input_error.h"
#include "maps/mrpt/mrpt_map_loader.h"
#include "workloads/delibot/motion_model.h"
#include "workloads/delibot/pose_estimate.h"
#include "workloads/delibot/resampling.h"
#include "workloads/delibot/scan_consistency.h"

namespace rc {
namespace {

using mrpt::maps::COccupancyGridMap2D;

void ConfigureLikelihood(const DelibotSettings& s, COccupancyGridMap2D& map) {
  auto& o = map.likelihoodOptions;
  if (s.sensor_model == SensorModelKind::kBeam) {
    o.likelihoodMethod = COccupancyGridMap2D::lmRayTracing;
    o.rayTracing_stdHit = static_cast<float>(s.beam.sigma_hit_m);
    o.rayTracing_decimation = s.mcl.beams.beam_step;
    o.rayTracing_useDistanceFilter = false;
  } else {
    o.likelihoodMethod = COccupancyGridMap2D::lmLikelihoodField_Thrun;
    o.LF_stdHit = static_cast<float>(s.likelihood.sigma_hit_m);
    o.LF_zHit = static_cast<float>(s.likelihood.z_hit);
    o.LF_zRandom = static_cast<float>(s.likelihood.z_rand);
    o.LF_maxCorrsDistance = static_cast<float>(s.likelihood.max_occ_dist_m);
    o.LF_maxRange = static_cast<float>(s.beam.max_range_m);
    o.LF_decimation = static_cast<uint32_t>(s.mcl.beams.beam_step);
    o.LF_useSquareDist = false;
    o.LF_alternateAverageMethod = false;
  }
}

mrpt::obs::CActionRobotMovement2D::TMotionModelOptions MotionOptions(const DelibotSettings& s) {
  mrpt::obs::CActionRobotMovement2D::TMotionModelOptions o;
  // Not mmThrun: MRPT 2.5.8 samples it through CPoseRandomSampler, which
  // returns the first sample of the particle pool every time, so every
  // particle would get the same increment (no motion noise at all).
  o.modelSelection = mrpt::obs::CActionRobotMovement2D::mmGaussian;
  auto& g = o.gaussianModel;
  // MRPT: sd_xy = a1 trans + a2 |dphi|, sd_phi = a3 trans + a4 |dphi| (m, rad).
  // Ours: variances alpha3 trans^2 + alpha4 rot^2 and alpha1 rot^2 + alpha2
  // trans^2, so each linear coefficient is the root of our matching alpha.
  g.a1 = std::sqrt(s.mcl.motion.alpha3);
  g.a2 = std::sqrt(s.mcl.motion.alpha4);
  g.a3 = std::sqrt(s.mcl.motion.alpha2);
  g.a4 = std::sqrt(s.mcl.motion.alpha1);
  g.minStdXY = 0.0;
  g.minStdPHI = 0.0;
  return o;
}

mrpt::bayes::CParticleFilter::TParticleFilterOptions FilterOptions(const DelibotSettings& s) {
  mrpt::bayes::CParticleFilter::TParticleFilterOptions o;
  o.PF_algorithm = mrpt::bayes::CParticleFilter::pfStandardProposal;
  o.resamplingMethod = mrpt::bayes::CParticleFilter::prSystematic;
  o.adaptiveSampleSize = false;
  o.BETA = s.mcl.resample_ess_fraction;
  o.sampleSize = static_cast<unsigned int>(s.mcl.particle_count);
  return o;
}

// Our scan as MRPT's observation: readings at or beyond the model's max
// range are flagged invalid, MRPT's "no return".
mrpt::obs::CObservation2DRangeScan::Ptr ToObservation(const LaserScan& scan, const LaserGeometry& g,
                                                      double max_range_m) {
  auto out = mrpt::obs::CObservation2DRangeScan::Create();
  out->aperture = static_cast<float>(g.angle_increment_rad * (g.beam_count - 1));
  out->rightToLeft = true;
  out->maxRange = static_cast<float>(max_range_m);
  out->sensorPose = mrpt::poses::CPose3D(g.offset_forward_m, 0.0, 0.0, g.angle_min_rad + 0.5 * out->aperture, 0.0, 0.0);
  out->resizeScan(scan.ranges_m.size());
  for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
    const bool valid = scan.ranges_m[i] < max_range_m;
    out->setScanRange(i, valid ? scan.ranges_m[i] : static_cast<float>(max_range_m));
    out->setScanRangeValidity(i, valid);
  }
  return out;
}

void Initialize(mrpt::slam::CMonteCarloLocalization2D& mcl, COccupancyGridMap2D& map, const DelibotSettings& s) {
  const std::size_t n = static_cast<std::size_t>(s.mcl.particle_count);
  if (!s.initial_pose) {
    // Our free cells are P(free) = 1 in MRPT's grid, unknown 0.5: the same set.
    mcl.resetUniformFreeSpace(&map, 0.7, static_cast<int>(n));
    return;
  }
  auto& random = mrpt::random::getRandomGenerator();
  mcl.resetDeterministic(mrpt::math::TPose2D(s.initial_pose->x, s.initial_pose->y, s.initial_pose->theta), n);
  for (auto& particle : mcl.m_particles) {
    particle.d.x += random.drawGaussian1D(0.0, s.initial_sigma_xy_m);
    particle.d.y += random.drawGaussian1D(0.0, s.initial_sigma_xy_m);
    particle.d.phi = WrapAngle(particle.d.phi + random.drawGaussian1D(0.0, s.initial_sigma_theta_rad));
    particle.log_w = 0.0;
  }
}

PoseEstimate EstimateFromMrpt(const mrpt::slam::CMonteCarloLocalization2D& mcl, const DelibotSettings& s) {
  std::vector<Pose2> particles;
  std::vector<double> log_weights;
  particles.reserve(mcl.m_particles.size());
  log_weights.reserve(mcl.m_particles.size());
  for (const auto& p : mcl.m_particles) {
    particles.push_back(Pose2{p.d.x, p.d.y, p.d.phi});
    log_weights.push_back(p.log_w);
  }
  NormalizeLogWeights(log_weights);
  return EstimatePose(particles, log_weights, s.mcl.estimate_kernel_radius_m);
}

Pose2 Compose(const Pose2& a, const mrpt::poses::CPose2D& increment) {
  const mrpt::poses::CPose2D c = mrpt::poses::CPose2D(a.x, a.y, a.theta) + increment;
  return Pose2{c.x(), c.y(), WrapAngle(c.phi())};
}

mrpt::poses::CPose2D Between(const Pose2& from, const Pose2& to) {
  return mrpt::poses::CPose2D(to.x, to.y, to.theta) - mrpt::poses::CPose2D(from.x, from.y, from.theta);
}

}  // namespace

DelibotResult RunMrptDelibot(const OccupancyGrid& grid, const SensorTrace& trace,
                             const std::vector<Pose2>* ground_truth, const DelibotSettings& settings,
                             const ProgressCallback& progress, const RowCallback& on_row) {
  InMemoryScanSource scans(trace);
  return RunMrptDelibot(grid, scans, ground_truth, settings, progress, on_row);
}

DelibotResult RunMrptDelibot(const OccupancyGrid& grid, ScanSource& scans, const std::vector<Pose2>* ground_truth,
                             const DelibotSettings& settings, const ProgressCallback& progress,
                             const RowCallback& on_row) {
  const LaserGeometry& geometry = scans.geometry();
  std::string error;
  if (!settings.mcl.IsValid(&error)) throw std::invalid_argument(error);
  if (!settings.beam.IsValid(&error)) throw std::invalid_argument("beam model: " + error);
  if (!settings.likelihood.IsValid(&error)) throw std::invalid_argument("likelihood model: " + error);
  if (settings.mcl.beams.beam_step > geometry.beam_count)
    throw std::invalid_argument("beam step exceeds the trace's beam count");
  // Options only our filter has are refused, not silently dropped: a run
  // meant to compare like with like would otherwise compare unlike.
  const MclOptions& o = settings.mcl;
  for (const auto& [given, option] : {std::pair{o.initial_particle_count != 0, "--initial-particles"},
                                      std::pair{o.hypothesis_floor.min_particles != 0, "--hypothesis-floor"},
                                      std::pair{o.max_particle_count != 0, "--max-particles"},
                                      std::pair{o.injection_check_updates != 0, "--injection-check"},
                                      std::pair{settings.audit_claims, "--claim-audit"}})
    if (given) throw UsageError(std::string("the MRPT engine has no counterpart of ") + option);
  if (ground_truth && ground_truth->size() != scans.size())
    throw std::invalid_argument("ground truth has " + std::to_string(ground_truth->size()) + " poses for " +
                                std::to_string(scans.size()) + " laser records");

  mrpt::random::getRandomGenerator().randomize(static_cast<uint32_t>(settings.mcl.seed));
  // Our map frame, unshifted: MRPT's estimates come out in our frame.
  auto map = std::make_shared<COccupancyGridMap2D>();
  ToMrptGrid(grid, 0.0, 0.0, *map);
  ConfigureLikelihood(settings, *map);

  mrpt::slam::CMonteCarloLocalization2D mcl;
  mcl.options.metricMap = map;
  mrpt::bayes::CParticleFilter filter;
  filter.m_options = FilterOptions(settings);
  Initialize(mcl, *map, settings);
  const auto motion_options = MotionOptions(settings);
  const RayCastScene exact_scene(grid, RayCastMethod::kDda);

  std::size_t count = scans.size();
  if (settings.max_records > 0) count = std::min<std::size_t>(count, settings.max_records);
  DelibotResult result;
  result.work_counted = false;
  result.rows.reserve(count);
  PoseEstimate last_estimate;
  Pose2 odometry_at_run;  // odometry of the last record the filter ran on
  double last_ess = static_cast<double>(settings.mcl.particle_count);
  double moved_d_m = 0.0, moved_a_rad = 0.0;
  LaserScan scan;  // one record at a time
  Pose2 previous_odometry;
  for (std::size_t k = 0; k < count; ++k) {
    if (!scans.Next(scan)) throw std::logic_error("the trace ended before its " + std::to_string(count) + " records");
    const auto start = std::chrono::steady_clock::now();
    // The same rule as ours (monte_carlo_localizer.cc) decides which records
    // update; MRPT's filter runs only on those.
    if (k > 0) {
      const OdometryDelta delta = ComputeOdometryDelta(previous_odometry, scan.odometry);
      moved_d_m += delta.trans;
      moved_a_rad += std::abs(delta.rot1) + std::abs(delta.rot2);
    }
    const bool run = k == 0 || moved_d_m >= settings.mcl.update_min_d_m || moved_a_rad >= settings.mcl.update_min_a_rad;
    DelibotRow row;
    if (run) {
      moved_d_m = moved_a_rad = 0.0;
      mrpt::obs::CActionCollection actions;
      if (k > 0) {
        mrpt::obs::CActionRobotMovement2D movement;
        movement.computeFromOdometry(Between(odometry_at_run, scan.odometry), motion_options);
        actions.insert(movement);
      }
      mrpt::obs::CSensoryFrame frame;
      frame.insert(ToObservation(scan, geometry, settings.beam.max_range_m));
      mrpt::bayes::CParticleFilter::TParticleFilterStats stats;
      filter.executeOn(mcl, k > 0 ? &actions : nullptr, &frame, &stats);
      last_estimate = EstimateFromMrpt(mcl, settings);
      last_ess = stats.ESS_beforeResample * static_cast<double>(mcl.m_particles.size());
      odometry_at_run = scan.odometry;
      row.sensor_updated = true;
      row.resampled = stats.ESS_beforeResample < filter.m_options.BETA;
      row.estimate = last_estimate.pose;
    } else {
      // Dead reckoning from the last filter run, as the filter's prediction would move it.
      row.estimate = Compose(last_estimate.pose, Between(odometry_at_run, scan.odometry));
    }
    row.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    row.iteration = static_cast<long>(k);
    row.time_s = scan.time_s;
    row.ess = last_ess;
    row.particles = mcl.m_particles.size();
    row.spread_m = last_estimate.spread_m;
    row.mode_weight = last_estimate.mode_weight;
    if (!JudgeDelibotRow(exact_scene, scan, geometry, settings, ground_truth ? &(*ground_truth)[k] : nullptr, row))
      result.summary.any_non_finite_weight = true;
    result.rows.push_back(row);
    if (on_row) on_row(row);
    previous_odometry = scan.odometry;
    if (progress) progress(k + 1, count);
  }
  const bool non_finite = result.summary.any_non_finite_weight;
  result.summary = SummarizeDelibot(result.rows, settings);
  result.summary.any_non_finite_weight = non_finite;
  return result;
}

nlohmann::json MrptSettingsJson(const DelibotSettings& s) {
  const auto motion = MotionOptions(s).gaussianModel;
  nlohmann::json likelihood;
  if (s.sensor_model == SensorModelKind::kBeam)
    likelihood = {{"likelihoodMethod", "lmRayTracing"},
                  {"rayTracing_stdHit_m", s.beam.sigma_hit_m},
                  {"rayTracing_decimation", s.mcl.beams.beam_step},
                  {"rayTracing_useDistanceFilter", false},
                  {"no_counterpart", {"z_short", "z_max", "z_rand", "lambda_short_per_m"}},
                  {"differs", "beams combined as a product (log domain) whatever --beam-combine says"}};
  else
    likelihood = {{"likelihoodMethod", "lmLikelihoodField_Thrun (LF_Trun)"},
                  {"LF_stdHit_m", s.likelihood.sigma_hit_m},
                  {"LF_zHit", s.likelihood.z_hit},
                  {"LF_zRandom", s.likelihood.z_rand},
                  {"LF_maxCorrsDistance_m", s.likelihood.max_occ_dist_m},
                  {"LF_maxRange_m", s.beam.max_range_m},
                  {"LF_decimation", s.mcl.beams.beam_step},
                  {"differs",
                   "hit term without the Gaussian's 1/(sigma sqrt(2 pi)); unsigned distance (0 inside walls) whatever "
                   "--lf-distance says; beams combined as a product (log domain) whatever --lf-combine says; unknown "
                   "cells as MRPT's field scores them whatever --lf-unknown says"}};
  return {{"algorithm", "CMonteCarloLocalization2D, pfStandardProposal"},
          {"sampleSize", s.mcl.particle_count},
          {"adaptiveSampleSize", false},
          {"resamplingMethod", "prSystematic"},
          {"BETA", s.mcl.resample_ess_fraction},
          {"motion_model",
           {{"modelSelection", "mmGaussian"},
            {"a1_m_per_m", motion.a1},
            {"a2_m_per_rad", motion.a2},
            {"a3_rad_per_m", motion.a3},
            {"a4_rad_per_rad", motion.a4},
            {"minStdXY_m", motion.minStdXY},
            {"minStdPHI_rad", motion.minStdPHI},
            {"mapping",
             "a1 = sqrt(alpha3), a2 = sqrt(alpha4), a3 = sqrt(alpha2), a4 = sqrt(alpha1): MRPT's "
             "deviations are linear in the motion, ours' variances quadratic"}}},
          {"likelihood", likelihood},
          {"ignored", {"recovery_alpha_slow", "recovery_alpha_fast", "ray_caster"}},
          {"random_generator", "mrpt::random::getRandomGenerator().randomize(seed)"}};
}

}  // namespace rc
