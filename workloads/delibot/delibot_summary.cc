// The run summary: totals, and the verdicts on a run's timeline (converged
// against the ground truth or by the filter's own claim, claims withdrawn,
// the end test, error and consistency statistics).
#include <algorithm>
#include <cmath>

#include "workloads/delibot/delibot_run.h"

namespace rc {
namespace {

constexpr int kSustainRecords = 10;

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

// The estimate moved more than the jump threshold since the previous record.
bool Jumped(const DelibotRow* previous, const DelibotRow& r, double jump_threshold_m) {
  return previous &&
         std::hypot(r.estimate.x - previous->estimate.x, r.estimate.y - previous->estimate.y) > jump_threshold_m;
}

struct ClaimHistory {
  long standing_from = -1;
  long withdrawn = 0;
};

// Replays the ground-truth-free claims record by record (see
// DelibotSummary::standing_claim_iteration): a claim is made after
// kSustainRecords consecutive localized sensor updates and withdrawn at the
// first jump or injection after it. A localized update that merely dips
// below a threshold breaks a run being built but withdraws no claim: one
// scan's consistency is noisy (a person, a poorly mapped door).
template <typename Localized>
ClaimHistory ReplayClaims(const std::vector<DelibotRow>& rows, const Localized& localized, double jump_threshold_m) {
  ClaimHistory h;
  int run = 0;
  long run_start = -1;
  const DelibotRow* previous = nullptr;
  for (const auto& r : rows) {
    const bool doubted = Jumped(previous, r, jump_threshold_m) || r.injected > 0;
    previous = &r;
    if (doubted) {
      if (h.standing_from >= 0) ++h.withdrawn;
      h.standing_from = -1;
      run = 0;
    }
    if (h.standing_from >= 0 || !r.sensor_updated) continue;
    if (!localized(r)) {
      run = 0;
      continue;
    }
    if (run++ == 0) run_start = r.iteration;
    if (run == kSustainRecords) h.standing_from = run_start;
  }
  return h;
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
  // (hypotheses_alive is 0 when the floor is off.)
  auto self_localized = [&](const DelibotRow& r) {
    return r.mode_weight >= s.converged_mode_weight && r.consistency >= s.converged_consistency &&
           r.hypotheses_alive <= 1;
  };
  auto localized = [&](const DelibotRow& r) {
    return gt ? (r.err_xy_m < s.converged_xy_m && r.err_theta_rad < s.converged_theta_rad) : self_localized(r);
  };
  // With ground truth every record is a check against the truth. Without,
  // only a sensor update adds evidence: a robot standing still for the first
  // 20 records of a log (robotdata1 does) would otherwise "converge" on the
  // weights of its very first scan.
  sum.self_convergence_iteration = FirstSustained(rows, self_localized, true);
  const ClaimHistory claims = ReplayClaims(rows, self_localized, s.jump_threshold_m);
  sum.standing_claim_iteration = claims.standing_from;
  sum.claims_withdrawn = claims.withdrawn;
  sum.convergence_iteration = gt ? FirstSustained(rows, localized, false) : sum.self_convergence_iteration;
  if (sum.convergence_iteration >= 0) {
    std::vector<double> exy, eth, cons;
    long consistent = 0;
    const DelibotRow* previous = nullptr;
    for (const auto& r : rows) {
      if (r.iteration < sum.convergence_iteration) continue;
      if (Jumped(previous, r, s.jump_threshold_m)) ++sum.jumps_after_convergence;
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
