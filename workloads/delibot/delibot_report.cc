#include "workloads/delibot/delibot_report.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "backends/backend.h"
#include "backends/scheduler/scheduler_cli.h"
#include "common/atomic_file.h"
#include "common/cpu_features.h"
#include "traces/csv_table.h"

namespace rc {
namespace {

CsvCell MaybeNumber(bool present, double value) { return present ? CsvCell(value) : CsvCell::Empty(); }

// "ttaplus-p" -> "ttaplus_p": column names stay identifiers.
std::string ColumnSafe(std::string name) {
  std::replace(name.begin(), name.end(), '-', '_');
  return name;
}

}  // namespace

DelibotTimeline::DelibotTimeline(std::string path, bool work_counted)
    : path_(std::move(path)), work_counted_(work_counted) {}

DelibotTimeline::~DelibotTimeline() = default;

void DelibotTimeline::Open(const DelibotRow& first) {
  ground_truth_ = first.has_ground_truth;
  priced_ = first.priced;
  std::vector<std::string> columns = {"iteration",
                                      "time_s",
                                      "est_x_m",
                                      "est_y_m",
                                      "est_theta_rad",
                                      "ess",
                                      "rays",
                                      "nodes",
                                      "nodes_per_ray",
                                      "wall_s",
                                      "sensor_updated",
                                      "log_mean_likelihood_nats",
                                      "resampled",
                                      "injected",
                                      "injection_rejected",
                                      "hypotheses_alive",
                                      "particles",
                                      "spread_m",
                                      "mode_weight",
                                      "consistency",
                                      "claim_audit",
                                      "claim_audit_margin_nats"};
  if (ground_truth_) {
    columns.push_back("err_xy_m");
    columns.push_back("err_theta_rad");
  }
  CsvTableOptions options;
  options.timeline = true;
  if (priced_) {
    // The ledger prices every modelled backend, in this order. (A first
    // record with no kernel work, as under the likelihood field, holds none.)
    backends_ = Backend::ModelledNames();
    if (first.pricing.priced && first.pricing.costs.size() != backends_.size())
      throw std::logic_error("a priced row holds " + std::to_string(first.pricing.costs.size()) +
                             " backend costs for " + std::to_string(backends_.size()) + " backends");
    for (const char* c : {"backend", "nodes_per_ray_prev", "threshold_nodes_per_ray", "switched"}) columns.push_back(c);
    for (const auto& b : backends_) columns.push_back("cycles_" + ColumnSafe(b));
    for (const char* c : {"simt_efficiency", "energy_j", "cum_cycles_policy"}) columns.push_back(c);
    for (const auto& b : backends_) columns.push_back("cum_cycles_" + ColumnSafe(b));
    // The hindsight oracle is known only when the run is over.
    options.hindsight_columns = {"cum_cycles_oracle", "oracle_backend"};
    cumulative_.assign(backends_.size(), 0.0);
  }
  table_ = std::make_unique<CsvTable>(path_, columns, options);
}

void DelibotTimeline::Add(const DelibotRow& r) {
  if (!table_) Open(r);
  std::vector<CsvCell> cells = {r.iteration,
                                r.time_s,
                                r.estimate.x,
                                r.estimate.y,
                                r.estimate.theta,
                                r.ess,
                                work_counted_ ? CsvCell(r.rays) : CsvCell::Empty(),
                                work_counted_ ? CsvCell(r.nodes) : CsvCell::Empty(),
                                MaybeNumber(work_counted_ && r.rays > 0, r.NodesPerRay()),
                                r.wall_s,
                                static_cast<int>(r.sensor_updated),
                                MaybeNumber(std::isfinite(r.log_mean_likelihood), r.log_mean_likelihood),
                                static_cast<int>(r.resampled),
                                r.injected,
                                r.injection_rejected,
                                r.hypotheses_alive,
                                r.particles,
                                r.spread_m,
                                r.mode_weight,
                                r.consistency,
                                ToString(r.claim_audit),
                                MaybeNumber(std::isfinite(r.claim_audit_margin_nats), r.claim_audit_margin_nats)};
  if (ground_truth_) {
    cells.emplace_back(r.err_xy_m);
    cells.emplace_back(r.err_theta_rad);
  }
  if (priced_) {
    const LedgerIteration& p = r.pricing;
    cells.emplace_back(p.backend);
    cells.push_back(MaybeNumber(p.nodes_per_query_prev >= 0, p.nodes_per_query_prev));
    cells.push_back(MaybeNumber(std::isfinite(p.threshold), p.threshold));
    cells.emplace_back(static_cast<int>(p.switched));
    for (std::size_t b = 0; b < backends_.size(); ++b)
      cells.emplace_back(p.priced ? static_cast<double>(p.costs[b].cycles) : 0.0);
    double efficiency = 0.0;
    bool has_efficiency = false;
    for (const BatchCost& c : p.costs)
      if (std::isfinite(c.simt_efficiency)) {
        efficiency = c.simt_efficiency;
        has_efficiency = true;
      }
    cells.push_back(MaybeNumber(has_efficiency, efficiency));
    cells.emplace_back(p.chosen_energy_j);
    cumulative_policy_ += p.chosen_cycles;
    cells.emplace_back(cumulative_policy_);
    for (std::size_t b = 0; b < backends_.size(); ++b) {
      if (p.priced) cumulative_[b] += static_cast<double>(p.costs[b].cycles);
      cells.emplace_back(cumulative_[b]);
    }
  }
  table_->AddRow(cells);
}

void DelibotTimeline::Finish(const DelibotResult& result) {
  if (!table_) {
    if (result.rows.empty()) throw std::logic_error("a DeliBot run without rows has no timeline");
    Open(result.rows.front());
  }
  if (table_->row_count() != result.rows.size())
    throw std::logic_error("the timeline holds " + std::to_string(table_->row_count()) + " rows for a run of " +
                           std::to_string(result.rows.size()) + " records");
  if (!priced_) {
    table_->Commit();
    return;
  }
  const LedgerSummary& ledger = result.pricing;
  table_->Commit([&](std::size_t row) {
    return std::vector<CsvCell>{ledger.oracle_cumulative_cycles.at(row), ledger.oracle_choice.at(row)};
  });
}

void WriteDelibotTimeline(const std::string& path, const DelibotResult& result) {
  DelibotTimeline timeline(path, result.work_counted);
  for (const DelibotRow& row : result.rows) timeline.Add(row);
  timeline.Finish(result);
}

nlohmann::json DelibotSummaryJson(const DelibotResult& result, const DelibotSettings& s, const DelibotProvenance& p) {
  using nlohmann::json;
  const DelibotSummary& m = result.summary;
  json config = {
      {"map", {{"path", p.map_path}, {"format", p.map_format}, {"value_convention", p.map_convention}}},
      {"trace", {{"path", p.trace_path}, {"format", p.trace_format}, {"ground_truth", p.ground_truth_path}}},
      {"particles", s.mcl.particle_count},
      {"initial_particles", std::max(s.mcl.particle_count, s.mcl.initial_particle_count)},
      {"max_particles", std::max(s.mcl.particle_count, s.mcl.max_particle_count)},
      {"seed", s.mcl.seed},
      {"beam_step", s.mcl.beams.beam_step},
      {"ray_caster", ToString(s.ray_caster)},
      {"sensor_model", ToString(s.sensor_model)},
      {"first_set_scoring", ToString(s.first_set_scoring)},
      {"audit_claims", s.audit_claims},
      {"claim_audit_scans", s.claim_audit_scans},
      {"max_range_m", s.beam.max_range_m},
      {"beam_model",
       {{"z_hit", s.beam.z_hit},
        {"z_short", s.beam.z_short},
        {"z_max", s.beam.z_max},
        {"z_rand", s.beam.z_rand},
        {"sigma_hit_m", s.beam.sigma_hit_m},
        {"lambda_short_per_m", s.beam.lambda_short_per_m},
        {"combine", ToString(s.beam.combination)}}},
      {"likelihood_field",
       {{"z_hit", s.likelihood.z_hit},
        {"z_rand", s.likelihood.z_rand},
        {"sigma_hit_m", s.likelihood.sigma_hit_m},
        {"max_occ_dist_m", s.likelihood.max_occ_dist_m},
        {"distance", s.likelihood.signed_distance ? "signed" : "unsigned"},
        {"unknown", s.likelihood.unknown_is_edge ? "edge" : "miss"},
        {"combine", ToString(s.likelihood.combination)}}},
      {"motion_noise",
       {{"alpha1", s.mcl.motion.alpha1},
        {"alpha2", s.mcl.motion.alpha2},
        {"alpha3", s.mcl.motion.alpha3},
        {"alpha4", s.mcl.motion.alpha4}}},
      {"resample_ess_fraction", s.mcl.resample_ess_fraction},
      {"hypothesis_floor_particles", s.mcl.hypothesis_floor.min_particles},
      {"hypothesis_window_nats", s.mcl.hypothesis_floor.window_nats},
      {"hypothesis_heading_bins", s.mcl.hypothesis_heading_bins},
      {"hypothesis_bin_m", s.mcl.estimate_kernel_radius_m},
      {"recovery_alpha_slow", s.mcl.alpha_slow},
      {"recovery_alpha_fast", s.mcl.alpha_fast},
      {"injection_check_updates", s.mcl.injection_check_updates},
      {"update_min_d_m", s.mcl.update_min_d_m},
      {"update_min_a_rad", s.mcl.update_min_a_rad},
      {"max_records", s.max_records},
      {"initialization", s.initial_pose ? "tracking" : "global"},
      {"threads", p.threads},
      // The widest SIMD code the run used (rcbench --simd): it changes the
      // host times only, never a result.
      {"simd", ToString(SimdInUse())},
  };
  if (s.initial_pose)
    config["initial_pose"] = {
        {"x_m", s.initial_pose->x}, {"y_m", s.initial_pose->y}, {"theta_rad", s.initial_pose->theta}};
  json totals = {{"records", m.records},
                 {"sensor_updates", m.sensor_updates},
                 {"rays", m.rays},
                 {"nodes", m.nodes},
                 {"nodes_per_ray", m.rays ? static_cast<double>(m.nodes) / m.rays : 0.0},
                 {"wall_s", m.wall_s},
                 {"wall_per_update_s", m.sensor_updates ? m.wall_s / m.sensor_updates : 0.0},
                 {"rays_per_s", m.wall_s > 0 ? m.rays / m.wall_s : 0.0},
                 {"resamples", m.resamples},
                 {"injected", m.injected},
                 {"injection_rejected", m.injection_rejected}};
  if (!result.work_counted)
    for (const char* key : {"rays", "nodes", "nodes_per_ray", "rays_per_s"}) totals[key] = nullptr;
  json accuracy = {{"convergence_iteration", m.convergence_iteration},
                   {"convergence_iteration_without_ground_truth", m.self_convergence_iteration},
                   {"standing_claim_iteration", m.standing_claim_iteration},
                   {"claims_withdrawn", m.claims_withdrawn},
                   {"claims_refused_by_audit", m.claims_refused},
                   {"converged_at_end", m.converged},
                   {"end_median_mode_weight", m.end_mode_weight},
                   {"end_median_consistency", m.end_consistency},
                   {"end_median_hypotheses_alive", m.end_hypotheses_alive},
                   {"median_consistency_after_convergence", m.median_consistency},
                   {"fraction_consistent_after_convergence", m.fraction_consistent},
                   {"jumps_after_convergence", m.jumps_after_convergence},
                   {"non_finite_weights", m.any_non_finite_weight},
                   {"criterion", p.ground_truth_path.empty()
                                     ? "mode weight >= " + std::to_string(s.converged_mode_weight) +
                                           " and consistency >= " + std::to_string(s.converged_consistency) +
                                           " for 10 sensor updates"
                                     : "error < " + std::to_string(s.converged_xy_m) + " m and < " +
                                           std::to_string(s.converged_theta_rad) + " rad for 10 records"}};
  if (!p.ground_truth_path.empty()) {
    accuracy["median_err_xy_m"] = m.median_err_xy_m;
    accuracy["p95_err_xy_m"] = m.p95_err_xy_m;
    accuracy["median_err_theta_rad"] = m.median_err_theta_rad;
    accuracy["final_err_xy_m"] = m.final_err_xy_m;
    accuracy["final_err_theta_rad"] = m.final_err_theta_rad;
  }
  json out = {{"workload", "delibot"}, {"config", config}, {"totals", totals}, {"accuracy", accuracy}};
  if (result.priced) {
    out["backends"] = LedgerSummaryJson(result.pricing, s.ledger);
    out["backends"]["pricing_host_s"] = result.pricing_wall_s;
    out["backends"]["prepare_host_s"] = result.prepare_wall_s;
    out["backends"]["filter_host_s"] = m.wall_s;
  }
  return out;
}

void WriteJsonFile(const std::string& path, const nlohmann::json& json) {
  AtomicFile file(path);
  file.stream() << json.dump(2) << "\n";
  file.Commit();
}

void PrintDelibotSummary(std::ostream& out, const DelibotResult& result, const DelibotSettings& s) {
  const DelibotSummary& m = result.summary;
  auto emit = [&out](const char* format, const auto&... args) {
    out << fmt::format(fmt::runtime(format), args...) << '\n';
  };
  if (s.mcl.injection_check_updates > 0)
    emit(
        "records                 {} ({} sensor updates, {} resamples, {} particles injected, {} refused "
        "by the injection check)",
        m.records, m.sensor_updates, m.resamples, m.injected, m.injection_rejected);
  else
    emit("records                 {} ({} sensor updates, {} resamples, {} particles injected)", m.records,
         m.sensor_updates, m.resamples, m.injected);
  if (s.sensor_model == SensorModelKind::kLikelihoodThenBeam && result.work_counted) {
    // Which model scored which records: only the beam model casts rays.
    long from = -1;
    unsigned long long lookups = 0, rays = 0, nodes = 0;
    for (const DelibotRow& r : result.rows) {
      if (r.tracking_stage && from < 0) from = r.iteration;
      (r.tracking_stage ? rays : lookups) += r.rays;
      if (r.tracking_stage) nodes += r.nodes;
    }
    if (from >= 0)
      emit(
          "sensor model            likelihood field up to record {} ({} end-point look-ups), beam model from "
          "record {} on (one hypothesis alive for {} updates)",
          from - 1, lookups, from, s.mcl.tracking_after_single_updates);
    else
      emit(
          "sensor model            likelihood field throughout ({} end-point look-ups): never one hypothesis "
          "alive for {} updates, so no ray was cast",
          lookups, s.mcl.tracking_after_single_updates);
    emit("rays                    {} cast by the beam model, {:.1f} nodes per ray", rays,
         rays ? static_cast<double>(nodes) / rays : 0.0);
    emit("host time               {:.3f} s total, {:.2f} ms per update", m.wall_s,
         m.sensor_updates ? 1e3 * m.wall_s / m.sensor_updates : 0.0);
  } else if (result.work_counted) {
    emit("rays                    {}, {:.1f} nodes per ray", static_cast<unsigned long long>(m.rays),
         m.rays ? static_cast<double>(m.nodes) / m.rays : 0.0);
    emit("host time               {:.3f} s total, {:.2f} ms per update, {:.2f} M rays/s", m.wall_s,
         m.sensor_updates ? 1e3 * m.wall_s / m.sensor_updates : 0.0, m.wall_s > 0 ? m.rays / m.wall_s / 1e6 : 0.0);
  } else {
    emit("host time               {:.3f} s total, {:.2f} ms per update", m.wall_s,
         m.sensor_updates ? 1e3 * m.wall_s / m.sensor_updates : 0.0);
  }
  const bool gt = !result.rows.empty() && result.rows.front().has_ground_truth;
  if (m.convergence_iteration >= 0 && (m.converged || gt)) {
    emit("converged at record     {} ({})", m.convergence_iteration,
         m.converged ? "still localized at the end" : "LOST by the end: error above the thresholds");
  } else if (m.convergence_iteration >= 0) {
    // Without ground truth a failed end test is not proof of being lost.
    emit(
        "converged at record     {} (not confirmed at the end: last 10 updates' median mode weight {:.2f}, "
        "consistency {:.2f}; {})",
        m.convergence_iteration, m.end_mode_weight, m.end_consistency,
        m.standing_claim_iteration < 0                ? "its claim was withdrawn and none stands"
        : m.end_mode_weight < s.converged_mode_weight ? "the belief is split"
        : m.end_hypotheses_alive > 1.0                ? "a rival hypothesis is still alive"
                                                      : "scans disagree with the map: wrong pose or wrong map");
  } else
    emit("converged at record     never");
  // With ground truth, also the record from which the filter itself claimed
  // to be localized: what a user without ground truth would have trusted.
  if (gt) {
    const char* rivals = s.mcl.hypothesis_floor.min_particles > 0 ? ", no rival hypothesis" : "";
    if (m.self_convergence_iteration >= 0)
      emit("filter's own claim      record {} (mode weight >= {:.2f} and consistency >= {:.2f}{} for 10 updates)",
           m.self_convergence_iteration, s.converged_mode_weight, s.converged_consistency, rivals);
    else
      emit("filter's own claim      never (mode weight >= {:.2f} and consistency >= {:.2f}{} for 10 updates)",
           s.converged_mode_weight, s.converged_consistency, rivals);
  }
  // A claim the filter later contradicted (a jump, injected particles) is
  // not one a user should keep trusting; say so, and which claim stands.
  if (m.claims_withdrawn > 0 || m.standing_claim_iteration != m.self_convergence_iteration) {
    const std::string standing = m.standing_claim_iteration >= 0 ? "the claim standing at the end is from record " +
                                                                       std::to_string(m.standing_claim_iteration)
                                                                 : std::string("no claim stands at the end");
    emit(
        "claims withdrawn        {} (the estimate jumped > {:.1f} m or random particles were injected after a "
        "claim); {}",
        m.claims_withdrawn, s.jump_threshold_m, standing.c_str());
  }
  if (s.audit_claims) {
    // The last refused audit's margin: how far the claimed place was from
    // standing out.
    const DelibotRow* last_refused = nullptr;
    for (const auto& r : result.rows)
      if (r.claim_audit == ClaimAuditOutcome::kRefused) last_refused = &r;
    if (last_refused)
      emit(
          "claims refused by audit {} (the claim's scans fit a place elsewhere within {:.1f} nats of the claimed one; "
          "last at record {}, margin {:.1f} nats)",
          m.claims_refused, s.mcl.hypothesis_floor.window_nats, last_refused->iteration,
          last_refused->claim_audit_margin_nats);
    else
      emit("claims refused by audit 0");
  }
  if (m.convergence_iteration >= 0) {
    emit("scan consistency        {:.3f} median after convergence (beams within {:.1f} sigma of the map)",
         m.median_consistency, s.consistency_sigmas);
    emit("jumps after convergence {} (estimate moved > {:.1f} m between two records)", m.jumps_after_convergence,
         s.jump_threshold_m);
  }
  if (!result.rows.empty() && result.rows.front().has_ground_truth) {
    if (m.convergence_iteration >= 0)
      emit("error after convergence {:.3f} m median, {:.3f} m p95, {:.4f} rad median heading", m.median_err_xy_m,
           m.p95_err_xy_m, m.median_err_theta_rad);
    else
      emit("error after convergence none (never converged)");
    emit("final error             {:.3f} m, {:.4f} rad", m.final_err_xy_m, m.final_err_theta_rad);
  }
  if (m.any_non_finite_weight) emit("WARNING: non-finite weights or estimates occurred");
  if (!result.priced) return;
  PrintLedgerSummary(out, result.pricing, s.ledger, s.backend_params.gpu.core_clock_hz, "update", "nodes per ray");
  // The cost models' own time; the filter's time includes what recording
  // adds to its casts (docs/pricing.md measures both end to end).
  emit("pricing host time       {:.3f} s in the cost models ({:.2f}x the filter's own, recording included there)",
       result.pricing_wall_s, m.wall_s > 0 ? result.pricing_wall_s / m.wall_s : 0.0);
}

}  // namespace rc
