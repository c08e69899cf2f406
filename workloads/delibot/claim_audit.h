#pragma once
// The claim audit: before the filter claims to be localized, it asks whether
// the scans the claim rests on single out the claimed place in the whole
// map. Why: the filter's own test ("no rival hypothesis alive") only sees
// the places its particles hold, and the dense first update keeps the few
// places that one scan happened to favour. On a map of look-alike places
// (64 rooms differing only in their doorways) the rivals are dropped there,
// not ruled out, and the test passes on a set that never held them
// (docs/defaults.md, "The claim audit").
//
// The audit draws poses uniformly over free space, as many as the auto-sized
// dense first set (so every place is sampled as finely as the first update
// sampled it), scores each on the latest scan, keeps the best
// kClaimAuditCandidates, and scores those on every audited scan, each replayed
// back through the odometry. It then compares the best candidate within the
// claimed place with the best outside it. Both are random poses at the same
// density, so neither has the advantage of the filter's refined estimate
// (which a random pose would never match). The claim passes when the claimed
// place leads by the filter's own rival window (hypothesis floor's
// window_nats): a place within that window would be a live rival.
#include <cstddef>
#include <cstdint>
#include <deque>
#include <limits>
#include <string>
#include <vector>

#include "common/angles.h"
#include "traces/sensor_trace.h"
#include "workloads/delibot/sensor_model.h"

namespace rc {

enum class ClaimAuditOutcome { kNotRun, kPassed, kRefused };
std::string ToString(ClaimAuditOutcome outcome);  // "", "passed", "refused"

// Candidates kept after the latest scan (a rule that acts as a model
// parameter: a place none of whose poses ranks among them on the latest
// scan is not compared). Unit: poses; range: >= 1. Source: the default cap
// on the set while rivals are alive (delibot_defaults.h, 20000), the places
// the filter itself can carry.
inline constexpr std::size_t kClaimAuditCandidates = 20000;

struct RememberedScan {
  LaserScan scan;
  LaserGeometry geometry;
};

// The claimed place: poses within radius_m and heading_rad of `pose`.
struct ClaimedPlace {
  Pose2 pose;
  double radius_m = 1.0;
  double heading_rad = 0.5;
};

struct ClaimAudit {
  ClaimAuditOutcome outcome = ClaimAuditOutcome::kNotRun;
  // Best candidate's log-likelihood over the audited scans within the
  // claimed place minus the best outside it (nats): -inf when no candidate
  // lies within the place, +inf when none lies outside.
  double margin_nats = std::numeric_limits<double>::quiet_NaN();
  Pose2 rival;                 // the best candidate outside the place (valid for a finite margin)
  std::size_t poses = 0;       // uniform poses drawn
  std::size_t candidates = 0;  // of them, scored on every audited scan
  std::uint64_t queries = 0;   // the model's queries (rays or end-point look-ups)
};

// scans: the audited scans, oldest first, the newest being where
// poses_now are (the odometry of each replays a pose back to it); at least
// one. poses_now: the uniform sample of free space. Passes when margin_nats
// >= window_nats.
ClaimAudit AuditClaim(SensorModel& model, const std::deque<RememberedScan>& scans, const BeamSelection& beams,
                      const std::vector<Pose2>& poses_now, const ClaimedPlace& place, double window_nats);

}  // namespace rc
