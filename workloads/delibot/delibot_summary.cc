// The run summary: totals, and the verdicts on a run's timeline (converged
// against the ground truth or by the filter's own claim, claims withdrawn,
// the end test, error and consistency statistics).
#include <algorithm>
#include <cmath>

#include "workloads/delibot/claim_replay.h"
#include "workloads/delibot/delibot_run.h"

namespace rc {
namespace {

double Median(std::vector<double> v) {
  if (v.empty()) return -1.0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

double Percentile(std::vector<double> v, double q) {
  if (v.empty()) return -1.0;
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(std::min<double>(v.size() - 1, std::floor(q * v.size())))];
}

// The last kSustainRecords sensor-updated rows, newest first.
std::vector<const DelibotRow*> LastUpdates(const std::vector<DelibotRow>& rows) {
  std::vector<const DelibotRow*> last;
  for (auto it = rows.rbegin(); it != rows.rend() && static_cast<int>(last.size()) < kSustainRecords; ++it)
    if (it->sensor_updated) last.push_back(&*it);
  return last;
}

// Without ground truth one scan's consistency is noisy (a person in front of
// the robot, a doorway), so "still localized at the end" asks that most of
// the last kSustainRecords sensor updates pass, not only the very last one.
template <typename Localized>
bool MostLocalized(const std::vector<const DelibotRow*>& last, const Localized& localized) {
  int passed = 0;
  for (const DelibotRow* r : last) passed += localized(*r) ? 1 : 0;
  return !last.empty() && 2 * passed > static_cast<int>(last.size());
}

// The first record of kSustainRecords consecutive localized rows (only
// sensor-updated rows count when updates_only), or -1.
template <typename Localized>
long FirstSustained(const std::vector<DelibotRow>& rows, const Localized& localized, bool updates_only) {
  int run = 0;
  long run_start = -1;
  for (const auto& r : rows) {
    if (updates_only && !r.sensor_updated) continue;
    if (!localized(r)) {
      run = 0;
      continue;
    }
    if (run++ == 0) run_start = r.iteration;
    if (run == kSustainRecords) return run_start;
  }
  return -1;
}

DelibotSummary Summarize(const std::vector<DelibotRow>& rows, const DelibotSettings& s) {
  DelibotSummary sum;
  sum.records = static_cast<long>(rows.size());
  for (const auto& r : rows) {
    sum.sensor_updates += r.sensor_updated;
    sum.rays += r.rays;
    sum.nodes += r.nodes;
    sum.wall_s += r.wall_s;
    sum.resamples += r.resampled;
    sum.injected += r.injected;
    sum.injection_rejected += r.injection_rejected;
  }
  const bool gt = !rows.empty() && rows.front().has_ground_truth;
  const std::vector<const DelibotRow*> last_updates = LastUpdates(rows);
  // With the hypothesis floor the filter also knows its rivals: while it
  // keeps a second hypothesis alive (within the window of the heaviest) it
  // does not claim to be localized, however much weight the first holds.
  auto self_localized = [&](const DelibotRow& r) { return SelfLocalized(r, s); };
  auto localized = [&](const DelibotRow& r) {
    return gt ? (r.err_xy_m < s.converged_xy_m && r.err_theta_rad < s.converged_theta_rad) : self_localized(r);
  };
  // With ground truth every record is a check against the truth. Without,
  // only a sensor update adds evidence: a robot standing still for the first
  // 20 records of a log (robotdata1 does) would otherwise "converge" on the
  // weights of its very first scan.
  sum.self_convergence_iteration = FirstSustained(rows, self_localized, true);
  // The claims as the run made them: a due claim its audit refused was not
  // made (claim_audit.h; a row without an audit refuses nothing).
  ClaimReplay claims(s.jump_threshold_m);
  for (const auto& r : rows)
    if (claims.Step(r, self_localized(r))) claims.Settle(r.claim_audit != ClaimAuditOutcome::kRefused);
  sum.standing_claim_iteration = claims.standing_from();
  sum.claims_withdrawn = claims.withdrawn();
  sum.claims_refused = claims.refused();
  // A claim its audit refused was never made: the filter's own claim is
  // then the first one made (-1 if every due claim was refused), not the
  // first that fell due.
  if (sum.claims_refused > 0) sum.self_convergence_iteration = claims.first_made_from();
  sum.convergence_iteration = gt ? FirstSustained(rows, localized, false) : sum.self_convergence_iteration;
  if (sum.convergence_iteration >= 0) {
    std::vector<double> exy, eth, cons;
    long consistent = 0;
    const DelibotRow* previous = nullptr;
    for (const auto& r : rows) {
      if (r.iteration < sum.convergence_iteration) continue;
      if (previous && Jumped(previous->estimate, r.estimate, s.jump_threshold_m)) ++sum.jumps_after_convergence;
      previous = &r;
      if (gt) {
        exy.push_back(r.err_xy_m);
        eth.push_back(r.err_theta_rad);
      }
      cons.push_back(r.consistency);
      consistent += r.consistency >= 0.5;
    }
    sum.median_err_xy_m = Median(exy);
    sum.p95_err_xy_m = Percentile(exy, 0.95);
    sum.median_err_theta_rad = Median(eth);
    sum.median_consistency = Median(cons);
    sum.fraction_consistent = cons.empty() ? 0.0 : static_cast<double>(consistent) / cons.size();
    // Without ground truth the filter is localized at the end only if a
    // claim still stands and most of the last updates pass.
    sum.converged =
        gt ? localized(rows.back()) : sum.standing_claim_iteration >= 0 && MostLocalized(last_updates, localized);
  }
  {
    std::vector<double> mode, cons, alive;
    for (const DelibotRow* r : last_updates) {
      mode.push_back(r->mode_weight);
      cons.push_back(r->consistency);
      alive.push_back(r->hypotheses_alive);
    }
    if (!mode.empty()) {
      sum.end_mode_weight = Median(mode);
      sum.end_consistency = Median(cons);
      sum.end_hypotheses_alive = Median(alive);
    }
  }
  if (gt && !rows.empty()) {
    sum.final_err_xy_m = rows.back().err_xy_m;
    sum.final_err_theta_rad = rows.back().err_theta_rad;
  }
  return sum;
}

}  // namespace

DelibotSummary SummarizeDelibot(const std::vector<DelibotRow>& rows, const DelibotSettings& settings) {
  return Summarize(rows, settings);
}

}  // namespace rc
