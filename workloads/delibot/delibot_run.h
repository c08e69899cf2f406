#pragma once
// One DeliBot run: a Monte Carlo localizer driven through a sensor trace,
// one timeline row per laser record, plus accuracy statistics.
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "backends/backend_params.h"
#include "backends/scheduler/backend_ledger.h"
#include "maps/occupancy_grid.h"
#include "robocore/ray_cast.h"
#include "traces/scan_source.h"
#include "traces/sensor_trace.h"
#include "workloads/delibot/beam_sensor_model.h"
#include "workloads/delibot/claim_audit.h"
#include "workloads/delibot/likelihood_field_model.h"
#include "workloads/delibot/mcl_options.h"
#include "workloads/delibot/staged_sensor_model.h"

namespace rc {

// kLikelihoodThenBeam: the likelihood field while the belief has rivals,
// the beam model once one hypothesis is left (staged_sensor_model.h).
enum class SensorModelKind { kBeam, kLikelihoodField, kLikelihoodThenBeam };
// "beam" | "likelihood" | "likelihood-then-beam"
SensorModelKind ParseSensorModelKind(const std::string& name);
// Whether the model casts rays that the backends can price.
bool CastsRays(SensorModelKind k);
std::string ToString(SensorModelKind k);

struct DelibotSettings {
  MclOptions mcl;
  SensorModelKind sensor_model = SensorModelKind::kBeam;
  // likelihood-then-beam only: which stage scores the dense first set's cut.
  FirstSetScoring first_set_scoring = FirstSetScoring::kGlobal;
  RayCastMethod ray_caster = RayCastMethod::kRayMarching;  // exact (= dda) and the fewest fetches
  BeamModelParams beam;                                    // max_range_m is shared by both models
  LikelihoodFieldParams likelihood;
  long max_records = 0;  // 0 = the whole trace
  // Tracking mode: start around this pose instead of uniformly.
  std::optional<Pose2> initial_pose;
  double initial_sigma_xy_m = 0.2;
  double initial_sigma_theta_rad = 0.1;
  // Ground-truth-free consistency: beams within this many sigma_hit.
  double consistency_sigmas = 3.0;
  // Thresholds that define "localized" for the summary.
  double converged_xy_m = 0.2;
  double converged_theta_rad = 5.0 * 3.14159265358979323846 / 180.0;
  // Ground-truth-free: the estimate's mode holds at least this share of the
  // weight (the rest may be recovery particles or a fading second mode), and
  // at least this fraction of the scan's beams is consistent with the map
  // at the estimate, for 10 consecutive sensor updates (records without a
  // sensor update bring no new evidence and do not count).
  double converged_mode_weight = 0.8;
  double converged_consistency = 0.5;
  // An estimate moving farther than this between two records is a jump:
  // the filter switched hypotheses (a robot does not teleport).
  double jump_threshold_m = 1.0;
  // Audit every claim as it falls due (claim_audit.h) and make it only if
  // the audit passes: the localizer keeps the last claim_audit_scans scans
  // (MclOptions::claim_audit_scans) and RunDelibot audits on them. Off in
  // these plain settings, on in DefaultDelibotSettings (`rcbench delibot`;
  // docs/defaults.md, "The claim audit").
  bool audit_claims = false;
  int claim_audit_scans = kClaimAuditScans;  // [1, 1000] sensor updates (--claim-audit-scans)
  // Shadow costing: every modelled backend prices every update's ray batch
  // (beam model only; the likelihood field casts no rays), and the policy
  // picks the backend that "ran". Off by default in the library (pricing
  // costs about 1.1-1.35x the unpriced run, docs/pricing.md); the CLI turns
  // it on unless --no-pricing.
  bool price_backends = false;
  BackendParameters backend_params;
  LedgerOptions ledger;
  // With price_backends: called once per update that launched kernel work,
  // with its launches (the injection check's batches first, then the
  // update's), after the ledger priced them and before they are dropped. An
  // update split into launches (kMaxRaysPerLaunch) passes each launch but
  // its last in a call of its own, as it is priced.
  // For a caller that prices the same run under other parameters as it goes
  // (the calibration's sensitivity sweep); the records keep the ledger's
  // address sample (LedgerOptions::replay_sms). With it set, every launch
  // of a split update is recorded (LedgerOptions::priced_launches does not
  // apply).
  std::function<void(const std::vector<const KernelRecord*>& launches)> on_priced_launches;
};

struct DelibotRow {
  long iteration = 0;  // 0-based index of the laser record in the trace
  double time_s = 0.0;
  Pose2 estimate;
  double ess = 0.0;
  std::uint64_t rays = 0;   // the update's queries plus the injection check's
  std::uint64_t nodes = 0;  // the same queries' node fetches
  double wall_s = 0.0;      // host time of the filter update
  bool sensor_updated = false;
  // The update's evidence: log of the weighted mean scan likelihood (nats),
  // the normalizer of Bayes' rule, which augmented MCL's averages also
  // track. Summed over updates it compares hypotheses: the difference of two
  // tracking runs' sums is their log Bayes factor. NaN without a sensor update
  // or for an engine that does not report it; finite after every update
  // (every beam density has a positive floor, z_rand / max_range).
  double log_mean_likelihood = std::numeric_limits<double>::quiet_NaN();
  bool resampled = false;
  int injected = 0;
  int injection_rejected = 0;  // random poses refused by the injection check
  // With the hypothesis floor: hypotheses within its window after the
  // update (1 = no rival; 0 = not computed). While a rival is alive the
  // filter does not claim convergence without ground truth.
  int hypotheses_alive = 0;
  // Particles after the update: particle_count, more for the dense first
  // set of global localization or while rivals grow the set.
  std::size_t particles = 0;
  // A staged sensor model's tracking model scored this record
  // (staged_sensor_model.h); false for one-stage models.
  bool tracking_stage = false;
  // A claim fell due at this record and was audited (audit_claims): the
  // outcome and its margin (ClaimAudit::margin_nats; NaN when not run).
  ClaimAuditOutcome claim_audit = ClaimAuditOutcome::kNotRun;
  double claim_audit_margin_nats = std::numeric_limits<double>::quiet_NaN();
  double spread_m = 0.0;
  double mode_weight = 0.0;  // normalized weight within 1 m of the estimate
  double consistency = 0.0;  // fraction of beams within k sigma at the estimate
  bool has_ground_truth = false;
  double err_xy_m = 0.0;
  double err_theta_rad = 0.0;
  double NodesPerRay() const { return rays > 0 ? static_cast<double>(nodes) / rays : 0.0; }
  bool priced = false;
  LedgerIteration pricing;      // valid when priced
  double pricing_wall_s = 0.0;  // host time spent pricing (not in wall_s)
};

struct DelibotSummary {
  long records = 0;
  long sensor_updates = 0;
  std::uint64_t rays = 0, nodes = 0;
  double wall_s = 0.0;
  long resamples = 0;
  long injected = 0;
  long injection_rejected = 0;
  // -1 when never reached. With ground truth: error below both thresholds for
  // 10 consecutive records; without: for 10 consecutive sensor updates, mode
  // weight and scan consistency at or above their thresholds and (with the
  // hypothesis floor) no rival hypothesis alive.
  long convergence_iteration = -1;
  // The ground-truth-free convergence (mode weight and consistency, as
  // above) even when ground truth is given: the record from which the
  // filter itself claims to be localized, which is all a user without
  // ground truth sees. Equal to convergence_iteration without ground truth.
  // With claim audits, a due claim its audit refused is not made: this is
  // then the record from which the first claim made was made.
  long self_convergence_iteration = -1;
  // A claim stands until the filter itself contradicts it: after the claim
  // its estimate jumps (> jump_threshold_m between two records) or it
  // injects random particles (augmented MCL's sign that the recent scans fit
  // worse than the long-run average). A contradicted claim is withdrawn, and
  // a new one needs kSustainRecords more localized updates. The record from
  // which the claim standing at the end was made (-1: none stands), and how
  // many claims were withdrawn before it.
  long standing_claim_iteration = -1;
  long claims_withdrawn = 0;
  // Due claims that their audit refused (audit_claims; 0 without).
  long claims_refused = 0;
  bool converged =
      false;  // also true at the end of the run (without ground truth: in most of the last 10 sensor updates)
  // Medians over the last 10 sensor updates, which the ground-truth-free
  // verdict at the end rests on: a low mode weight means the belief is
  // split; a high one with low consistency means the scans disagree with
  // the map there (a wrong pose, or a map that is wrong where the robot
  // is; without ground truth the two cannot be told apart). -1 if none.
  double end_mode_weight = -1.0;
  double end_consistency = -1.0;
  // The same median of hypotheses_alive: above 1, a rival hypothesis is
  // alive (hypothesis floor only; 0 without it).
  double end_hypotheses_alive = -1.0;
  double median_err_xy_m = -1.0, p95_err_xy_m = -1.0, median_err_theta_rad = -1.0;  // after convergence
  double final_err_xy_m = -1.0, final_err_theta_rad = -1.0;
  double median_consistency = 0.0;   // after convergence
  double fraction_consistent = 0.0;  // records after convergence with consistency >= 0.5
  long jumps_after_convergence = 0;  // estimate moves > jump_threshold_m between records
  bool any_non_finite_weight = false;
};

struct DelibotResult {
  std::vector<DelibotRow> rows;
  DelibotSummary summary;
  bool priced = false;
  LedgerSummary pricing;  // valid when priced
  double pricing_wall_s = 0.0;
  // Of pricing_wall_s, what the policy derived before the first update
  // (BackendLedger::Prepare, with the start probe's cast).
  double prepare_wall_s = 0.0;
  // False for an engine that does not report its kernel work (MRPT's
  // localizer): rays and nodes are then written as empty, not as 0.
  bool work_counted = true;
};

using ProgressCallback = std::function<void(std::size_t done, std::size_t total)>;
// Called with each row as soon as it is complete (the timeline streams them).
using RowCallback = std::function<void(const DelibotRow& row)>;

// Convergence, error and consistency statistics of a run's rows; shared with
// other engines (workloads/delibot/mrpt) so every engine is judged alike.
DelibotSummary SummarizeDelibot(const std::vector<DelibotRow>& rows, const DelibotSettings& settings);

// Judges one row whose estimate and ess are set: its scan consistency
// (beams within consistency_sigmas x sigma_hit of the range ray-cast from the
// estimate on `exact_scene`) and, with `truth`, its errors. Returns false if
// the row holds a non-finite ess or estimate. Shared with other engines
// (workloads/delibot/mrpt) so every engine's rows are judged alike.
bool JudgeDelibotRow(const RayCastScene& exact_scene, const LaserScan& scan, const LaserGeometry& geometry,
                     const DelibotSettings& settings, const Pose2* truth, DelibotRow& row);

// ground_truth: one pose per laser record of the trace (map frame), or null.
DelibotResult RunDelibot(const OccupancyGrid& grid, const SensorTrace& trace, const std::vector<Pose2>* ground_truth,
                         const DelibotSettings& settings, const ProgressCallback& progress = {},
                         const RowCallback& on_row = {});
// The same run pulling one record at a time from `scans` (a trace streamed
// from its file, traces/scan_source.h), so memory does not grow with it.
DelibotResult RunDelibot(const OccupancyGrid& grid, ScanSource& scans, const std::vector<Pose2>* ground_truth,
                         const DelibotSettings& settings, const ProgressCallback& progress = {},
                         const RowCallback& on_row = {});

}  // namespace rc
