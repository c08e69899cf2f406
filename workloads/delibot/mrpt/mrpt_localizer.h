#pragma once
// The reference engine: MRPT's own Monte Carlo localizer
// (mrpt::slam::CMonteCarloLocalization2D driven by mrpt::bayes::CParticleFilter)
// on the same OccupancyGrid and SensorTrace as ours, with our settings mapped
// onto MRPT's as closely as MRPT allows. It returns a DelibotResult, so the
// timeline, summary JSON and printed summary are written by the same code as
// ours (delibot_report.h); kernel work (rays, nodes) and backend costs are
// not MRPT's to report and stay empty.
//
// Settings and how they map (every approximate or missing match marked ~/-):
//   particles        = CParticleFilter sampleSize; KLD adaptive size off.
//   seed             = MRPT's global random generator, randomize(seed).
//                      Same seed -> same run, but a different random stream
//                      from ours, so runs agree statistically, not particle
//                      by particle.
//   ~ motion noise   MRPT's Gaussian odometry model (mmGaussian): one
//                    Gaussian over the increment (x, y, phi) with
//                    sd_xy = a1 trans + a2 |dphi| (the same in x and y) and
//                    sd_phi = a3 trans + a4 |dphi|, propagated through the
//                    increment's rotation. Ours (AMCL, Thrun's
//                    sample_motion_model_odometry) draws rot1, trans, rot2
//                    with variances alpha1 rot^2 + alpha2 trans^2 and
//                    alpha3 trans^2 + alpha4 rot^2. We set a1 = sqrt(alpha3),
//                    a2 = sqrt(alpha4), a3 = sqrt(alpha2), a4 = sqrt(alpha1),
//                    minStdXY = minStdPHI = 0: identical magnitudes when one
//                    term dominates, up to sqrt(2) wider when both are equal,
//                    and MRPT also spreads sideways as much as forward.
//                    MRPT's Thrun model (mmThrun) would match ours better,
//                    but in MRPT 2.5.8 MCL samples it through
//                    CPoseRandomSampler, which returns the first sample of
//                    its pre-drawn pool on every draw (measured: five draws,
//                    five identical increments), so every particle would
//                    move identically and the filter collapses to one pose.
//   beam model    ~  MRPT's lmRayTracing: one Gaussian of sigma_hit around
//                    the simulated range per beam; no short, max or random
//                    components (z_short, z_max, z_rand, lambda_short have
//                    no counterpart). rayTracing_stdHit = sigma_hit,
//                    rayTracing_decimation = beam step, distance filter off.
//   likelihood       MRPT's lmLikelihoodField_Thrun ("LF_Trun"):
//                    LF_stdHit = sigma_hit, LF_zHit = z_hit,
//                    LF_zRandom = z_rand, LF_maxCorrsDistance = distance
//                    cap, LF_maxRange = max range, LF_decimation = beam step.
//                  ~ Both score a beam end point at distance d (capped) as
//                    log(hit + z_rand / max_range), but MRPT's hit term is
//                    z_hit exp(-d^2 / 2 sigma^2) without the Gaussian's
//                    1 / (sigma sqrt(2 pi)) that ours has, so the balance of
//                    hit and random differs (by 2.0 at sigma 0.2 m).
//   resampling    =  prSystematic when ESS < BETA * N, BETA = ESS fraction.
//   - recovery       MRPT has no augmented-MCL injection: alpha_slow and
//                    alpha_fast are ignored (reported in the summary).
//   update_min_d/a = MRPT's filter runs on exactly the records where ours
//                    would update (same travel rule); the odometry between
//                    runs is applied as one accumulated increment, so its
//                    noise is drawn once per run rather than per record.
//                    Between runs the row's estimate is the last estimate
//                    moved by the odometry since (dead reckoning).
//   initialization = global: resetUniformFreeSpace over our free cells
//                    (written to MRPT's grid as P(free) = 1); tracking:
//                    Gaussian around the pose with our sigmas, drawn with
//                    MRPT's generator.
//   estimate       the same mean-shift mode estimate as ours
//                  (pose_estimate.h) over MRPT's particles and weights, so
//                  the two runs compare filters, not point estimators
//                  (MRPT's getMean() averages the modes of a global start).
//   wall time      MRPT's prediction, update and resampling plus the
//                  estimate, as ours.
#include <nlohmann/json.hpp>

#include "workloads/delibot/delibot_run.h"

namespace rc {

DelibotResult RunMrptDelibot(const OccupancyGrid& grid, const SensorTrace& trace,
                             const std::vector<Pose2>* ground_truth, const DelibotSettings& settings,
                             const ProgressCallback& progress = {}, const RowCallback& on_row = {});
DelibotResult RunMrptDelibot(const OccupancyGrid& grid, ScanSource& scans, const std::vector<Pose2>* ground_truth,
                             const DelibotSettings& settings, const ProgressCallback& progress = {},
                             const RowCallback& on_row = {});

// The MRPT settings actually used, and the ones of ours that have no
// counterpart, for the summary JSON.
nlohmann::json MrptSettingsJson(const DelibotSettings& settings);

}  // namespace rc
