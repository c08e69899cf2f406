#include "workloads/delibot/delibot_run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "robocore/ray_batch_recorded.h"
#include "workloads/delibot/claim_replay.h"
#include "workloads/delibot/monte_carlo_localizer.h"
#include "workloads/delibot/scan_consistency.h"
#include "workloads/delibot/staged_sensor_model.h"
#include "workloads/delibot/start_probe.h"

namespace rc {
namespace {

std::unique_ptr<SensorModel> MakeSensorModel(const OccupancyGrid& grid, const DelibotSettings& s) {
  auto beam = [&] {
    return std::make_unique<BeamSensorModel>(std::make_shared<RayCastScene>(grid, s.ray_caster), s.beam);
  };
  auto field = [&] {
    LikelihoodFieldParams lf = s.likelihood;
    lf.max_range_m = s.beam.max_range_m;
    return std::make_unique<LikelihoodFieldModel>(grid, lf);
  };
  if (s.sensor_model == SensorModelKind::kBeam) return beam();
  if (s.sensor_model == SensorModelKind::kLikelihoodField) return field();
  return std::make_unique<StagedSensorModel>(field(), beam(), s.first_set_scoring);
}

}  // namespace

SensorModelKind ParseSensorModelKind(const std::string& name) {
  if (name == "beam") return SensorModelKind::kBeam;
  if (name == "likelihood") return SensorModelKind::kLikelihoodField;
  if (name == "likelihood-then-beam") return SensorModelKind::kLikelihoodThenBeam;
  throw std::invalid_argument("unknown sensor model '" + name +
                              "' (expected beam, likelihood or likelihood-then-beam)");
}

std::string ToString(SensorModelKind k) {
  switch (k) {
    case SensorModelKind::kBeam: return "beam";
    case SensorModelKind::kLikelihoodField: return "likelihood";
    case SensorModelKind::kLikelihoodThenBeam: return "likelihood-then-beam";
  }
  return "?";
}

bool CastsRays(SensorModelKind k) { return k != SensorModelKind::kLikelihoodField; }

bool JudgeDelibotRow(const RayCastScene& exact_scene, const LaserScan& scan, const LaserGeometry& geometry,
                     const DelibotSettings& settings, const Pose2* truth, DelibotRow& row) {
  row.consistency = MeasureScanConsistency(exact_scene, row.estimate, scan, geometry, settings.beam.max_range_m,
                                           settings.consistency_sigmas * settings.beam.sigma_hit_m)
                        .Fraction();
  if (truth) {
    row.has_ground_truth = true;
    row.err_xy_m = std::hypot(row.estimate.x - truth->x, row.estimate.y - truth->y);
    row.err_theta_rad = std::abs(WrapAngle(row.estimate.theta - truth->theta));
  }
  return std::isfinite(row.ess) && std::isfinite(row.estimate.x) && std::isfinite(row.estimate.y);
}

DelibotResult RunDelibot(const OccupancyGrid& grid, const SensorTrace& trace, const std::vector<Pose2>* ground_truth,
                         const DelibotSettings& settings, const ProgressCallback& progress, const RowCallback& on_row) {
  InMemoryScanSource scans(trace);
  return RunDelibot(grid, scans, ground_truth, settings, progress, on_row);
}

DelibotResult RunDelibot(const OccupancyGrid& grid, ScanSource& scans, const std::vector<Pose2>* ground_truth,
                         const DelibotSettings& settings, const ProgressCallback& progress, const RowCallback& on_row) {
  const LaserGeometry& geometry = scans.geometry();
  std::string error;
  if (!settings.beam.IsValid(&error)) throw std::invalid_argument("beam model: " + error);
  if (!settings.likelihood.IsValid(&error)) throw std::invalid_argument("likelihood model: " + error);
  if (settings.mcl.beams.beam_step > geometry.beam_count)
    throw std::invalid_argument("beam step exceeds the trace's beam count");
  if (ground_truth && ground_truth->size() != scans.size())
    throw std::invalid_argument("ground truth has " + std::to_string(ground_truth->size()) + " poses for " +
                                std::to_string(scans.size()) + " laser records");

  const bool price = settings.price_backends && CastsRays(settings.sensor_model);
  MclOptions mcl_options = settings.mcl;
  mcl_options.record_kernel = price;
  if (settings.audit_claims) mcl_options.claim_audit_scans = settings.claim_audit_scans;
  std::unique_ptr<BackendLedger> ledger;
  // Pricing's host time of the launches an update was split into, which
  // runs inside the filter's update: moved from the filter's time to
  // pricing's.
  double split_pricing_s = 0.0;
  if (price) {
    ledger = std::make_unique<BackendLedger>(settings.backend_params, settings.ledger);
    mcl_options.record_sample = ledger->RecordSample();
    mcl_options.price_launch = [&](const KernelRecord& launch) {
      const auto start = std::chrono::steady_clock::now();
      ledger->AddLaunch(launch);
      if (settings.on_priced_launches) settings.on_priced_launches({&launch});
      split_pricing_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
    // A caller that prices every launch itself needs every launch recorded.
    if (!settings.on_priced_launches) {
      mcl_options.launch_sample.priced = settings.ledger.priced_launches;
      mcl_options.estimate_launches = [&](const EstimatedLaunches& estimated) { ledger->AddLaunchesLike(estimated); };
    }
  }
  MonteCarloLocalizer mcl(grid, MakeSensorModel(grid, settings), mcl_options);
  if (settings.initial_pose)
    mcl.InitializeAround(*settings.initial_pose, settings.initial_sigma_xy_m, settings.initial_sigma_theta_rad);
  else
    mcl.InitializeUniform();
  double prepare_wall_s = 0.0;
  if (ledger) {
    // What the policy derives before the first update (a threshold, or
    // where to start) depends on the kernel's program, its memory layout
    // and the batch size (launch overhead is amortized over the batch), all
    // known before the first update: record one ray for the layout.
    const auto prepare_start = std::chrono::steady_clock::now();
    const RayCastScene scene(grid, settings.ray_caster);
    RecordOptions record_options = RecordOptionsFor(settings.ray_caster, settings.mcl.record_choices);
    record_options.sample = ledger->RecordSample();
    RayBatch one;
    one.max_range_m = settings.beam.max_range_m;
    const std::vector<std::uint32_t> free_cells = grid.FreeCellIndices();
    if (!free_cells.empty()) {
      const double r = grid.resolution_m();
      one.queries.push_back(
          {(free_cells[0] / grid.size_y() + 0.5) * r, (free_cells[0] % grid.size_y() + 0.5) * r, 0.0});
      std::vector<RayHit> hits;
      KernelRecord layout;
      CastRayBatchRecorded(scene, one, hits, layout,
                           RecordOptionsFor(settings.ray_caster, settings.mcl.record_choices));
      // A ray of length L crosses at most sqrt(2) L / r + 2 cells (march
      // samples fewer; rm fetches a subset of dda's cells).
      const auto max_nodes =
          static_cast<std::uint32_t>(std::ceil(std::sqrt(2.0) * settings.beam.max_range_m / grid.resolution_m()) + 2);
      const int beams = settings.mcl.beams.Count(geometry.beam_count);
      // Where to start: the first priced update's batch as drawn in
      // advance (start_probe.h), cast only for a policy that starts from
      // it. That update scores the initial set with the beam model, except
      // under a staged model in global localization: its beam model first
      // scores the set cut to particle_count when it takes over, wherever
      // the filter has converged by then (which the probe cannot know: it
      // draws from the initial distribution, the whole free space).
      const std::size_t first_particles = settings.sensor_model == SensorModelKind::kBeam || settings.initial_pose
                                              ? mcl.particles().size()
                                              : static_cast<std::size_t>(settings.mcl.particle_count);
      KernelRecord start_probe;
      if (ledger->ChoosesStart())
        start_probe = CastStartProbe(mcl, scene, geometry, settings.mcl.beams, settings.beam.max_range_m,
                                     StartProbePoses(first_particles, beams), settings.mcl.seed, record_options);
      ledger->Prepare(layout, static_cast<std::size_t>(settings.mcl.particle_count) * beams, max_nodes, &start_probe);
    }
    prepare_wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - prepare_start).count();
  }
  const RayCastScene exact_scene(grid, RayCastMethod::kDda);

  std::size_t count = scans.size();
  if (settings.max_records > 0) count = std::min<std::size_t>(count, settings.max_records);
  DelibotResult result;
  result.rows.reserve(count);
  LaserScan scan;  // one record at a time: memory does not grow with the trace
  ClaimReplay claims(settings.jump_threshold_m);
  for (std::size_t k = 0; k < count; ++k) {
    if (!scans.Next(scan)) throw std::logic_error("the trace ended before its " + std::to_string(count) + " records");
    if (ledger) ledger->BeginIteration();
    const auto start = std::chrono::steady_clock::now();
    split_pricing_s = 0.0;
    const MclStepResult step = mcl.Update(scan, geometry, k);
    const PoseEstimate estimate = mcl.Estimate();
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() - split_pricing_s;

    DelibotRow row;
    row.iteration = static_cast<long>(k);
    row.time_s = scan.time_s;
    row.estimate = estimate.pose;
    row.ess = step.ess;
    row.sensor_updated = step.sensor_updated;
    if (step.sensor_updated) row.log_mean_likelihood = step.log_mean_likelihood;
    row.resampled = step.resampled;
    row.injected = step.injected;
    row.injection_rejected = step.injection_rejected;
    row.hypotheses_alive = step.hypotheses_alive;
    row.particles = mcl.particles().size();
    row.tracking_stage = step.tracking;
    if (step.work) {
      row.rays = step.work->rays;
      row.nodes = step.work->nodes;
    }
    // The injection check's casts are part of the record's work.
    row.rays += step.check_rays;
    row.nodes += step.check_nodes;
    row.wall_s = wall;
    if (ledger) {
      const auto pricing_start = std::chrono::steady_clock::now();
      const bool ran = step.sensor_updated && step.work && step.work->rays > 0;
      if (step.check_records)
        for (const KernelRecord& check : *step.check_records) ledger->AddLaunch(check);
      row.pricing = ledger->EndIteration(ran ? &step.work->record : nullptr);
      row.priced = true;
      row.pricing_wall_s =
          split_pricing_s + std::chrono::duration<double>(std::chrono::steady_clock::now() - pricing_start).count();
      if (settings.on_priced_launches) {
        std::vector<const KernelRecord*> launches;
        if (step.check_records)
          for (const KernelRecord& check : *step.check_records) launches.push_back(&check);
        if (ran) launches.push_back(&step.work->record);
        if (!launches.empty()) settings.on_priced_launches(launches);
      }
    }
    row.spread_m = estimate.spread_m;
    row.mode_weight = estimate.mode_weight;
    if (!JudgeDelibotRow(exact_scene, scan, geometry, settings, ground_truth ? &(*ground_truth)[k] : nullptr, row))
      result.summary.any_non_finite_weight = true;
    if (settings.audit_claims && claims.Step(row, SelfLocalized(row, settings))) {
      const auto audit_start = std::chrono::steady_clock::now();
      const ClaimAudit audit = mcl.AuditClaim(row.estimate, k);
      row.wall_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - audit_start).count();
      row.claim_audit = audit.outcome;
      row.claim_audit_margin_nats = audit.margin_nats;
      claims.Settle(audit.outcome == ClaimAuditOutcome::kPassed);
    }
    result.rows.push_back(row);
    if (on_row) on_row(row);
    if (progress) progress(k + 1, count);
  }
  const bool non_finite = result.summary.any_non_finite_weight;
  result.summary = SummarizeDelibot(result.rows, settings);
  result.summary.any_non_finite_weight = non_finite;
  if (ledger) {
    result.priced = true;
    result.pricing = ledger->Finish();
    // What the policy derived before the first update (its start probe
    // included) is part of pricing's cost.
    result.prepare_wall_s = prepare_wall_s;
    result.pricing_wall_s = prepare_wall_s;
    for (const auto& row : result.rows) result.pricing_wall_s += row.pricing_wall_s;
  }
  return result;
}

}  // namespace rc
