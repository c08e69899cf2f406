#include "workloads/delibot/claim_audit.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "common/pose_algebra.h"
#include "workloads/delibot/best_indices.h"

namespace rc {
namespace {

bool InPlace(const Pose2& pose, const ClaimedPlace& place) {
  return std::hypot(pose.x - place.pose.x, pose.y - place.pose.y) <= place.radius_m &&
         std::abs(WrapAngle(pose.theta - place.pose.theta)) <= place.heading_rad;
}

// Each pose's log-likelihood summed over the audited scans from index
// `first` on, the pose replayed back to each scan through the odometry
// since.
std::vector<double> ScoreOnScans(SensorModel& model, const std::deque<RememberedScan>& scans,
                                 const BeamSelection& beams, const std::vector<Pose2>& poses_now,
                                 SensorUpdateWork& work, ClaimAudit& audit, std::size_t first = 0) {
  std::vector<double> total(poses_now.size(), 0.0), scores;
  std::vector<Pose2> replayed(poses_now.size());
  const Pose2& odometry_now = scans.back().scan.odometry;
  for (std::size_t s = first; s < scans.size(); ++s) {
    const RememberedScan& remembered = scans[s];
    const Pose2 back = Between(odometry_now, remembered.scan.odometry);
    for (std::size_t j = 0; j < poses_now.size(); ++j) replayed[j] = Compose(poses_now[j], back);
    model.SelectionLogLikelihoods(replayed, remembered.scan, remembered.geometry, beams, scores, work);
    audit.queries += work.rays;
    for (std::size_t j = 0; j < poses_now.size(); ++j) total[j] += scores[j];
  }
  return total;
}

struct Refined {
  std::vector<Pose2> poses;
  std::vector<double> totals;
};

// Pattern search on the audited scans' summed log-likelihood from each
// start: at each step size, move to the best of the six neighbours
// (+-x, +-y, +-theta) while it improves and stays in free space, then halve
// the steps. All starts advance together, one batch per scan.
Refined Refine(SensorModel& model, const std::deque<RememberedScan>& scans, const BeamSelection& beams,
               const OccupancyGrid& grid, std::vector<Pose2> starts, SensorUpdateWork& work, ClaimAudit& audit) {
  Refined r;
  r.totals = ScoreOnScans(model, scans, beams, starts, work, audit);
  r.poses = std::move(starts);
  const std::size_t n = r.poses.size();
  double step_xy = kClaimAuditRefineStartXyM, step_theta = kClaimAuditRefineStartThetaRad;
  for (int level = 0; level < kClaimAuditRefineLevels; ++level, step_xy /= 2, step_theta /= 2) {
    std::vector<bool> settled(n, false);
    for (int move = 0; move < kClaimAuditRefineMoves; ++move) {
      std::vector<Pose2> trial;
      std::vector<std::size_t> owner;
      for (std::size_t i = 0; i < n; ++i) {
        if (settled[i]) continue;
        const Pose2& p = r.poses[i];
        for (const Pose2& d : {Pose2{step_xy, 0, 0}, Pose2{-step_xy, 0, 0}, Pose2{0, step_xy, 0}, Pose2{0, -step_xy, 0},
                               Pose2{0, 0, step_theta}, Pose2{0, 0, -step_theta}}) {
          const Pose2 q{p.x + d.x, p.y + d.y, WrapAngle(p.theta + d.theta)};
          if (!grid.IsFreePoint(q.x, q.y)) continue;
          trial.push_back(q);
          owner.push_back(i);
        }
      }
      if (trial.empty()) break;
      const std::vector<double> scores = ScoreOnScans(model, scans, beams, trial, work, audit);
      std::vector<double> best = r.totals;
      std::vector<Pose2> best_pose = r.poses;
      for (std::size_t t = 0; t < trial.size(); ++t)
        if (scores[t] > best[owner[t]]) {
          best[owner[t]] = scores[t];
          best_pose[owner[t]] = trial[t];
        }
      bool moved = false;
      for (std::size_t i = 0; i < n; ++i) {
        if (settled[i]) continue;
        if (best[i] > r.totals[i]) {
          r.totals[i] = best[i];
          r.poses[i] = best_pose[i];
          moved = true;
        } else {
          settled[i] = true;
        }
      }
      if (!moved) break;
    }
  }
  return r;
}

// Compares the refined places: the first claimed_starts and any refined
// into the claimed place are the claimed place, the rest rivals. Sets the
// margin, the best rival and the outcome; returns the rival places after a
// refusal (those it remembers), none after a pass.
std::vector<Pose2> Compare(const Refined& refined, std::size_t claimed_starts, const ClaimedPlace& place,
                           double window_nats, ClaimAudit& audit) {
  const double inf = std::numeric_limits<double>::infinity();
  double best_in = -inf, best_out = -inf;
  for (std::size_t r = 0; r < refined.poses.size(); ++r) {
    const double t = refined.totals[r];
    if (r < claimed_starts || InPlace(refined.poses[r], place)) {
      best_in = std::max(best_in, t);
    } else if (t > best_out) {
      best_out = t;
      audit.rival = refined.poses[r];
    }
  }
  audit.margin_nats = best_out == -inf ? inf : best_in - best_out;
  audit.outcome = audit.margin_nats >= window_nats ? ClaimAuditOutcome::kPassed : ClaimAuditOutcome::kRefused;
  std::vector<Pose2> rivals;
  if (audit.outcome == ClaimAuditOutcome::kRefused)
    for (std::size_t r = claimed_starts; r < refined.poses.size(); ++r)
      if (!InPlace(refined.poses[r], place)) rivals.push_back(refined.poses[r]);
  return rivals;
}

// The dense stage on `poses`: the best `keep` on the latest scan and every
// pose within the claimed place, scored on the candidate scans; the
// claimed place and the rival places refined and compared. Sets the audit's
// counts, margin and outcome; returns the compared rival places after a
// refusal, none after a pass.
std::vector<Pose2> AuditOnPoses(SensorModel& model, const OccupancyGrid& grid, const std::deque<RememberedScan>& scans,
                                const BeamSelection& beams, const std::vector<Pose2>& poses, std::size_t keep,
                                const ClaimedPlace& place, double window_nats, SensorUpdateWork& work,
                                ClaimAudit& audit) {
  audit.poses = poses.size();
  // The best on the latest scan, and every pose within the claimed place
  // (which is compared whether or not it ranks among them).
  std::vector<std::size_t> kept =
      model.BestSelection(poses, scans.back().scan, scans.back().geometry, beams, keep, work);
  audit.queries += work.rays;
  std::vector<bool> is_kept(poses.size(), false);
  for (std::size_t i : kept) is_kept[i] = true;
  for (std::size_t i = 0; i < poses.size(); ++i)
    if (!is_kept[i] && InPlace(poses[i], place)) kept.push_back(i);
  audit.candidates = kept.size();
  std::vector<Pose2> candidates(kept.size());
  for (std::size_t j = 0; j < kept.size(); ++j) candidates[j] = poses[kept[j]];
  const std::size_t first = scans.size() - std::min(scans.size(), kClaimAuditCandidateScans);
  const std::vector<double> total = ScoreOnScans(model, scans, beams, candidates, work, audit, first);

  // Places to refine: the claimed one from the filter's estimate and from
  // its best candidate, then the rival places.
  std::vector<Pose2> starts = {place.pose};
  std::size_t best_in_place = candidates.size();
  for (std::size_t j = 0; j < candidates.size(); ++j)
    if (InPlace(candidates[j], place) && (best_in_place == candidates.size() || total[j] > total[best_in_place]))
      best_in_place = j;
  if (best_in_place < candidates.size()) starts.push_back(candidates[best_in_place]);
  const std::size_t claimed_starts = starts.size();
  for (const Pose2& rival : RivalPlaces(candidates, total, place)) starts.push_back(rival);
  audit.places = starts.size() - claimed_starts;
  const Refined refined = Refine(model, scans, beams, grid, std::move(starts), work, audit);
  return Compare(refined, claimed_starts, place, window_nats, audit);
}

}  // namespace

std::string ToString(ClaimAuditOutcome outcome) {
  switch (outcome) {
    case ClaimAuditOutcome::kNotRun: return "";
    case ClaimAuditOutcome::kPassed: return "passed";
    case ClaimAuditOutcome::kRefused: return "refused";
  }
  return "";
}

std::vector<Pose2> RivalPlaces(const std::vector<Pose2>& candidates, const std::vector<double>& totals,
                               const ClaimedPlace& place) {
  if (candidates.size() != totals.size()) throw std::invalid_argument("one total per candidate");
  std::vector<std::size_t> order(candidates.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return totals[a] > totals[b]; });
  std::vector<Pose2> best, spread;
  auto in_any = [&](const Pose2& pose, const std::vector<Pose2>& places) {
    for (const Pose2& p : places)
      if (InPlace(pose, {p, place.radius_m, place.heading_rad})) return true;
    return false;
  };
  // The best places, each from its best candidate (a candidate within the
  // bin of a place already taken belongs to it).
  for (std::size_t j : order) {
    if (best.size() >= kClaimAuditRivals) break;
    if (!InPlace(candidates[j], place) && !in_any(candidates[j], best)) best.push_back(candidates[j]);
  }
  // The best place of each region away from the claim: a candidate farther
  // than two bin radii from the claimed place and from every place taken
  // for spread, at any heading.
  const double spacing_m = 2.0 * place.radius_m;
  auto far_from = [&](const Pose2& pose, const Pose2& p) { return std::hypot(pose.x - p.x, pose.y - p.y) > spacing_m; };
  for (std::size_t j : order) {
    if (spread.size() >= kClaimAuditSpreadRivals) break;
    const Pose2& c = candidates[j];
    if (!far_from(c, place.pose) || in_any(c, best)) continue;
    bool far = true;
    for (const Pose2& p : spread) far = far && far_from(c, p);
    if (far) spread.push_back(c);
  }
  best.insert(best.end(), spread.begin(), spread.end());
  return best;
}

ClaimAudit AuditClaim(SensorModel& model, const OccupancyGrid& grid, const std::deque<RememberedScan>& scans,
                      const BeamSelection& beams, const std::function<std::vector<Pose2>()>& draw_poses,
                      const ClaimedPlace& place, double window_nats, RememberedRivals& rivals) {
  if (scans.empty()) throw std::invalid_argument("a claim audit needs at least one scan");
  ClaimAudit audit;
  SensorUpdateWork work;  // host-side: the audit is not a priced launch
  const Pose2& odometry_now = scans.back().scan.odometry;

  // The re-check: the rivals of the last refusal, moved by the odometry
  // since, against the claimed place.
  if (!rivals.places.empty()) {
    const Pose2 moved = Between(rivals.odometry, odometry_now);
    std::vector<Pose2> starts = {place.pose};
    for (const Pose2& p : rivals.places) {
      const Pose2 q = Compose(p, moved);
      if (grid.IsFreePoint(q.x, q.y)) starts.push_back(q);
    }
    audit.places = starts.size() - 1;
    const Refined refined = Refine(model, scans, beams, grid, std::move(starts), work, audit);
    std::vector<Pose2> compared = Compare(refined, 1, place, window_nats, audit);
    if (audit.outcome == ClaimAuditOutcome::kRefused) {
      audit.rechecked = true;
      rivals = {std::move(compared), odometry_now};
      return audit;
    }
    const std::uint64_t rechecked_queries = audit.queries;
    audit = ClaimAudit{};
    audit.queries = rechecked_queries;
  }

  const std::vector<Pose2> poses_now = draw_poses();
  // The claim's neighbourhood first: a refusal needs only one rival, and
  // there most are (a room's own ambiguity); only a pass needs the whole
  // map. The neighbourhood keeps the same share of candidates as of poses.
  std::vector<Pose2> near;
  for (const Pose2& p : poses_now)
    if (std::hypot(p.x - place.pose.x, p.y - place.pose.y) <= kClaimAuditNeighbourhoodM) near.push_back(p);
  if (!near.empty() && near.size() < poses_now.size()) {
    const std::size_t keep = std::max<std::size_t>(
        1,
        static_cast<std::size_t>(std::ceil(static_cast<double>(kClaimAuditCandidates) *
                                           static_cast<double>(near.size()) / static_cast<double>(poses_now.size()))));
    std::vector<Pose2> compared = AuditOnPoses(model, grid, scans, beams, near, keep, place, window_nats, work, audit);
    if (audit.outcome == ClaimAuditOutcome::kRefused) {
      audit.neighbourhood = true;
      rivals = {std::move(compared), odometry_now};
      return audit;
    }
  }
  rivals = {AuditOnPoses(model, grid, scans, beams, poses_now, kClaimAuditCandidates, place, window_nats, work, audit),
            odometry_now};
  return audit;
}

}  // namespace rc
