#include "workloads/delibot/claim_audit.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "common/pose_algebra.h"

namespace rc {
namespace {

bool InPlace(const Pose2& pose, const ClaimedPlace& place) {
  return std::hypot(pose.x - place.pose.x, pose.y - place.pose.y) <= place.radius_m &&
         std::abs(WrapAngle(pose.theta - place.pose.theta)) <= place.heading_rad;
}

// Indices of the `keep` highest scores, best first; ties go to the lower
// index, so the choice is the same on every run (NaN ranks last).
std::vector<std::size_t> BestIndices(const std::vector<double>& scores, std::size_t keep) {
  std::vector<std::size_t> order(scores.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  auto score = [&](std::size_t i) {
    return std::isnan(scores[i]) ? -std::numeric_limits<double>::infinity() : scores[i];
  };
  auto better = [&](std::size_t a, std::size_t b) { return score(a) > score(b) || (score(a) == score(b) && a < b); };
  keep = std::min(keep, order.size());
  std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(keep), order.end(), better);
  order.resize(keep);
  return order;
}

}  // namespace

std::string ToString(ClaimAuditOutcome outcome) {
  switch (outcome) {
    case ClaimAuditOutcome::kNotRun:
      return "";
    case ClaimAuditOutcome::kPassed:
      return "passed";
    case ClaimAuditOutcome::kRefused:
      return "refused";
  }
  return "";
}

ClaimAudit AuditClaim(SensorModel& model, const std::deque<RememberedScan>& scans, const BeamSelection& beams,
                      const std::vector<Pose2>& poses_now, const ClaimedPlace& place, double window_nats) {
  if (scans.empty()) throw std::invalid_argument("a claim audit needs at least one scan");
  ClaimAudit audit;
  audit.poses = poses_now.size();
  SensorUpdateWork work;  // host-side: the audit is not a priced launch
  std::vector<double> latest;
  model.SelectionLogLikelihoods(poses_now, scans.back().scan, scans.back().geometry, beams, latest, work);
  audit.queries += work.rays;

  const std::vector<std::size_t> kept = BestIndices(latest, kClaimAuditCandidates);
  audit.candidates = kept.size();
  std::vector<Pose2> candidates(kept.size()), replayed(kept.size());
  std::vector<double> total(kept.size());
  for (std::size_t j = 0; j < kept.size(); ++j) {
    candidates[j] = poses_now[kept[j]];
    total[j] = latest[kept[j]];
  }
  const Pose2& odometry_now = scans.back().scan.odometry;
  std::vector<double> scores;
  for (std::size_t s = 0; s + 1 < scans.size(); ++s) {
    // Where each candidate was at that scan if the odometry since is right.
    const Pose2 back = Between(odometry_now, scans[s].scan.odometry);
    for (std::size_t j = 0; j < candidates.size(); ++j) replayed[j] = Compose(candidates[j], back);
    model.SelectionLogLikelihoods(replayed, scans[s].scan, scans[s].geometry, beams, scores, work);
    audit.queries += work.rays;
    for (std::size_t j = 0; j < candidates.size(); ++j) total[j] += scores[j];
  }

  const double inf = std::numeric_limits<double>::infinity();
  double best_in = -inf, best_out = -inf;
  for (std::size_t j = 0; j < candidates.size(); ++j) {
    const double t = std::isnan(total[j]) ? -inf : total[j];
    if (InPlace(candidates[j], place)) {
      best_in = std::max(best_in, t);
    } else if (t > best_out || (best_out == -inf && t == -inf)) {
      best_out = t;
      audit.rival = candidates[j];
    }
  }
  const bool any_out = std::any_of(candidates.begin(), candidates.end(),
                                   [&](const Pose2& p) { return !InPlace(p, place); });
  if (!any_out)
    audit.margin_nats = inf;
  else if (best_in == -inf)
    audit.margin_nats = -inf;
  else
    audit.margin_nats = best_in - best_out;  // +inf when every pose outside is ruled out
  audit.outcome = audit.margin_nats >= window_nats ? ClaimAuditOutcome::kPassed : ClaimAuditOutcome::kRefused;
  return audit;
}

}  // namespace rc
