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
// sampled it), scores each on the latest scan with the place model's sharp
// selection scoring (the likelihood field's product), keeps the best
// kClaimAuditCandidates and every pose within the claimed place, and scores
// those on every audited scan, each replayed back through the odometry. The
// best of them are only samples: the best of millions of poses over many
// places lands nearer its place's optimum than the best of the few hundred
// within one place, so comparing samples favours rivals (and comparing the
// filter's refined estimate with samples would favour the claim). So the
// claimed place (from the estimate and from its best sample) and the
// kClaimAuditRivals best other places (from their best samples), with the
// best place of each region away from the claim (RivalPlaces), are each
// refined by a pattern search on the same scans, and their optima compared.
// The claim passes when the claimed place leads the best rival by the
// filter's own rival window (the hypothesis floor's window_nats): a place
// within it would be a live rival.
//
// The dense stage runs first on the uniform poses in the claim's
// neighbourhood (kClaimAuditNeighbourhoodM), where most rivals are; a
// refusal there ends the audit, and only then does the whole map's sample
// run, which a pass needs.
//
// A refused audit remembers the rival places it compared. The next audit
// first moves them by the odometry since, refines them and the claimed
// place, and refuses at once if one is within the window: a rival found
// once need not be found again by a new dense sample, which is the audit's
// cost. All compared rivals are kept, not only those within the window: a
// rival a few nats outside it may come within it on the next scans (on a
// map of look-alike rooms keeping them cut the dense samples from 11 to 7,
// docs/defaults.md). Only a full audit passes a claim.
#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "common/angles.h"
#include "maps/occupancy_grid.h"
#include "traces/sensor_trace.h"
#include "workloads/delibot/sensor_model.h"

namespace rc {

enum class ClaimAuditOutcome { kNotRun, kPassed, kRefused };
std::string ToString(ClaimAuditOutcome outcome);  // "", "passed", "refused"

// Scans a claim is audited on by default (--claim-audit-scans): the latest
// ones, at most this many (fewer when fewer sensor updates ran). Unit:
// sensor updates; range: [1, 1000]. Source: the claim's own evidence, its
// kSustainRecords localized updates. Longer windows replay the scans
// through the odometry as one rigid path, which its drift bends: with 60,
// chosen on seen runs, the audit passed two wrong claims on held-out ones
// (docs/defaults.md, "The claim audit").
inline constexpr int kClaimAuditScans = 10;

// Candidates kept after the latest scan (a rule that acts as a model
// parameter: a place none of whose poses ranks among them on the latest
// scan is not compared). Unit: poses; range: >= 1. Source: the default cap
// on the set while rivals are alive (delibot_defaults.h, 20000), the places
// the filter itself can carry.
inline constexpr std::size_t kClaimAuditCandidates = 20000;
// Scans the candidates are scored on before places are chosen: the latest
// ones, at most this many (the refinement uses every audited scan). Unit:
// sensor updates; range: >= 1. Source: the claim's own evidence, its
// kSustainRecords localized updates (claim_replay.h); it bounds the dense
// stage's cost whatever the audited window.
inline constexpr std::size_t kClaimAuditCandidateScans = 10;

// The claim's neighbourhood, audited first on the uniform poses within this
// distance of the claimed pose: a refusal there ends the audit, and only a
// pass goes on to the whole map (a rule that acts as a model parameter: a
// rival within it refuses a claim that the whole map's audit, which
// compares only the best and most spread places, might have passed). Why:
// a refusal needs one rival, and most are near the claim (on 64room_005
// the refusals came from places 1-4 m from it; docs/defaults.md), while
// the whole map's dense stage is the audit's cost (about 4 s on one thread
// on the MovingAI maps). Unit: m; range: > 0. Source: those refusals' 4 m.
inline constexpr double kClaimAuditNeighbourhoodM = 4.0;

// Rival places refined and compared (a rule that acts as a model parameter:
// a place ranked below them by its best sample is not compared). Unit:
// places; range: >= 1. Source: assumption; each costs about 400 poses
// scored on every audited scan, small beside the uniform poses.
inline constexpr std::size_t kClaimAuditRivals = 32;
// Rival places taken for spread besides them: the best place of each region
// away from the claim (RivalPlaces). Why: the best places crowd near the
// claim, where a room's own ambiguity gives many bins that fit, and a
// far look-alike that fits as well can rank below all of them (on
// 64room_005 the true room's best pose ranked 129th; docs/defaults.md).
// Unit: places; range: >= 0. Source: assumption, as many as the best
// places.
inline constexpr std::size_t kClaimAuditSpreadRivals = 32;
// The refinement's first steps and how often they halve. Unit: m, rad,
// count. Source: the first steps are about the spacing of the auto first
// set's poses (4 within 0.15 m and 3 deg, mcl_options.h); four halvings end
// at 12.5 mm and 6 mrad, below a map cell (>= 25 mm on the shipped maps) and
// a beam's angular step. Moves per step: at most kClaimAuditRefineMoves.
inline constexpr double kClaimAuditRefineStartXyM = 0.1;        // (0, 1] m
inline constexpr double kClaimAuditRefineStartThetaRad = 0.05;  // (0, 0.5] rad
inline constexpr int kClaimAuditRefineLevels = 4;               // [1, 10]
inline constexpr int kClaimAuditRefineMoves = 10;               // [1, 100]

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

// Rival places a refused audit leaves for the next one, as poses at the
// time of `odometry` (the newest audited scan's odometry).
struct RememberedRivals {
  std::vector<Pose2> places;
  Pose2 odometry;
};

struct ClaimAudit {
  ClaimAuditOutcome outcome = ClaimAuditOutcome::kNotRun;
  // Refused by re-checking the remembered rivals, without a dense sample.
  bool rechecked = false;
  // Refused by the claim's neighbourhood (kClaimAuditNeighbourhoodM); the
  // counts below are then the neighbourhood's.
  bool neighbourhood = false;
  // The claimed place's refined log-likelihood over the audited scans minus
  // the best rival place's (nats); +inf when no rival place was found.
  double margin_nats = std::numeric_limits<double>::quiet_NaN();
  Pose2 rival;                 // the best rival place's refined pose (valid for a finite margin)
  std::size_t poses = 0;       // uniform poses drawn
  std::size_t candidates = 0;  // of them, scored on the latest kClaimAuditCandidateScans scans
  std::size_t places = 0;      // rival places refined
  std::uint64_t queries = 0;   // the model's queries (rays or end-point look-ups)
};

// The rival places an audit refines, from candidates ranked by their totals
// on the latest kClaimAuditCandidateScans scans (best first; ties keep the
// candidates' order): the kClaimAuditRivals best places outside the
// claimed one, each from its best candidate, then up to
// kClaimAuditSpreadRivals more, the best candidate of each region farther
// than two bin radii (2 radius_m) from the claimed place and from every
// other place taken for spread.
std::vector<Pose2> RivalPlaces(const std::vector<Pose2>& candidates, const std::vector<double>& totals,
                               const ClaimedPlace& place);

// scans: the audited scans, oldest first, the newest being where the
// poses are (the odometry of each replays a pose back to it); at least
// one. draw_poses: the uniform sample of free space, drawn only for a full
// audit. grid: refinement moves stay in its free space. Passes when
// margin_nats >= window_nats. rivals: read (a re-check first when it holds
// places) and replaced: the rival places compared after a refusal, none
// after a pass.
ClaimAudit AuditClaim(SensorModel& model, const OccupancyGrid& grid, const std::deque<RememberedScan>& scans,
                      const BeamSelection& beams, const std::function<std::vector<Pose2>()>& draw_poses,
                      const ClaimedPlace& place, double window_nats, RememberedRivals& rivals);

}  // namespace rc
