// The claim audit (workloads/delibot/claim_audit.h): a claim is made only if
// the claim's scans single out the claimed place among poses sampled over
// the whole map at equal density. On a map with a twin place it is refused,
// in an asymmetric room the true place passes and a wrong one is refused,
// and a run with audits on still claims where nothing looks alike, with
// the same audits at any thread count.
#include <algorithm>
#include <cmath>
#include <deque>
#include <vector>

#include <gtest/gtest.h>
#include <omp.h>

#include "common/random_stream.h"
#include "same_rows.h"
#include "synthetic_world.h"
#include "workloads/delibot/best_indices.h"
#include "workloads/delibot/claim_audit.h"
#include "workloads/delibot/delibot_run.h"
#include "workloads/delibot/likelihood_field_model.h"

namespace rc {
namespace {

constexpr double kWindowNats = 6.0;  // the defaults' rival window

// Marks the cells [xa, xb] x [ya, yb] occupied.
void Block(OccupancyGrid& g, int xa, int ya, int xb, int yb) {
  for (int x = xa; x <= xb; ++x)
    for (int y = ya; y <= yb; ++y) g.Set(x, y, CellState::kOccupied);
}

// Two identical rooms side by side, 10 m x 7.5 m each at 0.125 m (exact in
// binary, so a pose shifted by one room maps onto the same cells): each has
// its own walls, a pillar and a box, placed so that nothing inside a room
// looks alike.
OccupancyGrid TwinRooms() {
  OccupancyGrid g(160, 60, 0.125);
  for (const int x0 : {0, 80}) {
    Block(g, x0, 0, x0 + 79, 1);
    Block(g, x0, 58, x0 + 79, 59);
    Block(g, x0, 0, x0 + 1, 59);
    Block(g, x0 + 78, 0, x0 + 79, 59);
    Block(g, x0 + 20, 38, x0 + 23, 41);  // pillar
    Block(g, x0 + 50, 8, x0 + 60, 14);   // box
  }
  return g;
}

std::vector<Pose2> UniformFreePoses(const OccupancyGrid& g, std::size_t n, double max_x_m, std::uint64_t seed) {
  std::vector<Pose2> poses;
  RandomStream stream(seed, StreamPurpose::kTest, 0, 0);
  while (poses.size() < n) {
    const Pose2 p{stream.Uniform(0.0, max_x_m), stream.Uniform(0.0, g.size_y() * g.resolution_m()),
                  stream.Uniform(-kPi, kPi)};
    if (g.IsFreePoint(p.x, p.y)) poses.push_back(p);
  }
  return poses;
}

// The poses followed by each one's twin, dx_m farther along x.
std::vector<Pose2> WithTwins(std::vector<Pose2> poses, double dx_m) {
  const std::size_t first_room = poses.size();
  for (std::size_t i = 0; i < first_room; ++i) poses.push_back({poses[i].x + dx_m, poses[i].y, poses[i].theta});
  return poses;
}

// The last `count` scans of a run, as the localizer remembers them.
std::deque<RememberedScan> LastScans(const test::SyntheticRun& run, std::size_t count) {
  std::deque<RememberedScan> scans;
  for (std::size_t k = run.trace.scans.size() - count; k < run.trace.scans.size(); ++k)
    scans.push_back({run.trace.scans[k], run.trace.geometry});
  return scans;
}

TEST(ClaimAuditTest, ATwinPlaceSampledAsDenselyIsARival) {
  const OccupancyGrid g = TwinRooms();
  const test::SyntheticRun run = test::DriveThrough(g, {{1.5, 2.0, 0}, {4.0, 3.5, 0}}, 0.05, 0.0, 1);
  LikelihoodFieldModel model(g, LikelihoodFieldParams{});
  // Poses in the first room and each one's twin in the second: every pose
  // in the claimed place has a twin that fits the scans as well.
  const std::vector<Pose2> poses = WithTwins(UniformFreePoses(g, 100000, 10.0, 2), 10.0);
  const ClaimedPlace place{run.truth.back(), 1.0, 2.0 * kPi / 12};
  int draws = 0;
  auto draw = [&] {
    ++draws;
    return poses;
  };
  RememberedRivals rivals;
  const std::deque<RememberedScan> scans = LastScans(run, 10);
  const ClaimAudit audit = AuditClaim(model, g, scans, BeamSelection{6}, draw, place, kWindowNats, rivals);
  EXPECT_EQ(audit.outcome, ClaimAuditOutcome::kRefused) << audit.margin_nats;
  EXPECT_FALSE(audit.rechecked);
  EXPECT_FALSE(audit.neighbourhood);  // the twin is 10 m away: the whole map's stage found it
  EXPECT_LT(std::abs(audit.margin_nats), kWindowNats);
  EXPECT_NEAR(audit.rival.x, run.truth.back().x + 10.0, 0.5);  // the twin place
  EXPECT_NEAR(audit.rival.y, run.truth.back().y, 0.5);
  EXPECT_EQ(audit.poses, poses.size());
  EXPECT_GE(audit.candidates, kClaimAuditCandidates);  // and the claimed place's own poses
  EXPECT_GE(audit.places, 1u);
  EXPECT_EQ(draws, 1);

  // The twin is remembered, and the next audit refuses on it without a
  // dense sample.
  ASSERT_FALSE(rivals.places.empty());
  const ClaimAudit again = AuditClaim(model, g, scans, BeamSelection{6}, draw, place, kWindowNats, rivals);
  EXPECT_EQ(again.outcome, ClaimAuditOutcome::kRefused);
  EXPECT_TRUE(again.rechecked);
  EXPECT_EQ(draws, 1);
  EXPECT_EQ(again.poses, 0u);
  EXPECT_NEAR(again.rival.x, run.truth.back().x + 10.0, 0.5);
  EXPECT_LT(std::abs(again.margin_nats), kWindowNats);
}

// Two identical 3 m rooms whose centres are 3.5 m apart (0.125 m cells, exact
// in binary), each with a box that makes it asymmetric inside.
OccupancyGrid NearTwinRooms() {
  OccupancyGrid g(52, 24, 0.125);
  for (const int x0 : {0, 28}) {
    Block(g, x0, 0, x0 + 23, 0);
    Block(g, x0, 23, x0 + 23, 23);
    Block(g, x0, 0, x0, 23);
    Block(g, x0 + 23, 0, x0 + 23, 23);
    Block(g, x0 + 15, 14, x0 + 18, 18);  // box
  }
  Block(g, 24, 0, 27, 23);  // between the rooms
  return g;
}

TEST(ClaimAuditTest, ATwinInTheClaimsNeighbourhoodRefusesBeforeTheWholeMapIsScored) {
  const OccupancyGrid g = NearTwinRooms();
  const test::SyntheticRun run = test::DriveThrough(g, {{0.8, 0.8, 0}, {1.4, 2.2, 0}}, 0.05, 0.0, 1);
  LikelihoodFieldModel model(g, LikelihoodFieldParams{});
  const std::vector<Pose2> poses = WithTwins(UniformFreePoses(g, 15000, 3.0, 3), 3.5);
  auto draw = [&] { return poses; };
  const ClaimedPlace place{run.truth.back(), 1.0, 2.0 * kPi / 12};
  std::size_t near = 0;
  for (const Pose2& p : poses) near += std::hypot(p.x - place.pose.x, p.y - place.pose.y) <= kClaimAuditNeighbourhoodM;
  ASSERT_LT(near, poses.size());  // some of the twin room is beyond the neighbourhood
  RememberedRivals rivals;
  const ClaimAudit audit = AuditClaim(model, g, LastScans(run, 10), BeamSelection{6}, draw, place, kWindowNats, rivals);
  EXPECT_EQ(audit.outcome, ClaimAuditOutcome::kRefused) << audit.margin_nats;
  EXPECT_TRUE(audit.neighbourhood);
  EXPECT_EQ(audit.poses, near);  // only the neighbourhood was scored
  EXPECT_NEAR(audit.rival.x, run.truth.back().x + 3.5, 0.5);
  EXPECT_NEAR(audit.rival.y, run.truth.back().y, 0.5);
  EXPECT_FALSE(rivals.places.empty());
}

TEST(ClaimAuditTest, TheTruePlaceOfAnAsymmetricRoomPassesAndAWrongOneIsRefused) {
  const OccupancyGrid g = test::AsymmetricRoom();
  // The last 10 scans face the pillar and the box (by the tour's end, in
  // the corner by the inner wall, a corner seen from its other side fits
  // within a few nats: the audit rightly refuses there).
  const test::SyntheticRun run = test::DriveThrough(g, {{5.5, 3.0, 0}, {7.5, 3.0, 0}}, 0.05, 0.03, 3);
  LikelihoodFieldModel model(g, LikelihoodFieldParams{});
  // The auto first set's density: 3395 poses per m^2 of free space.
  const std::vector<Pose2> poses = UniformFreePoses(g, 300000, 12.0, 4);
  auto draw = [&] { return poses; };
  const std::deque<RememberedScan> scans = LastScans(run, 10);
  const Pose2 truth = run.truth.back();
  RememberedRivals none;
  const ClaimAudit right =
      AuditClaim(model, g, scans, BeamSelection{6}, draw, {truth, 1.0, 2.0 * kPi / 12}, kWindowNats, none);
  EXPECT_EQ(right.outcome, ClaimAuditOutcome::kPassed)
      << right.margin_nats << " nats; rival at " << right.rival.x << ", " << right.rival.y;
  EXPECT_GE(right.margin_nats, kWindowNats);
  EXPECT_TRUE(none.places.empty());
  const Pose2 wrong{truth.x, truth.y + 4.0, truth.theta};
  RememberedRivals rivals;
  const ClaimAudit refused =
      AuditClaim(model, g, scans, BeamSelection{6}, draw, {wrong, 1.0, 2.0 * kPi / 12}, kWindowNats, rivals);
  EXPECT_EQ(refused.outcome, ClaimAuditOutcome::kRefused);
  EXPECT_LT(refused.margin_nats, 0.0);
  EXPECT_LT(std::hypot(refused.rival.x - truth.x, refused.rival.y - truth.y), 1.0);  // the true place
  // The true place, remembered as the wrong claim's rival, does not stop a
  // right claim: the re-check clears it, and a full audit passes and
  // forgets the rivals.
  ASSERT_FALSE(rivals.places.empty());
  const ClaimAudit after =
      AuditClaim(model, g, scans, BeamSelection{6}, draw, {truth, 1.0, 2.0 * kPi / 12}, kWindowNats, rivals);
  EXPECT_EQ(after.outcome, ClaimAuditOutcome::kPassed);
  EXPECT_FALSE(after.rechecked);
  EXPECT_EQ(after.margin_nats, right.margin_nats);
  EXPECT_TRUE(rivals.places.empty());
}

TEST(ClaimAuditTest, ARunWithAuditsClaimsWhereNothingLooksAlike) {
  const OccupancyGrid g = test::AsymmetricRoom();
  const test::SyntheticRun run = test::DriveThrough(g, test::RoomTour(), 0.15, 0.03, 11);
  DelibotSettings s;
  s.mcl.particle_count = 2000;
  s.mcl.beams.beam_step = 6;
  s.beam.max_range_m = 12.0;
  s.sensor_model = SensorModelKind::kLikelihoodField;
  s.audit_claims = true;
  omp_set_num_threads(1);
  const DelibotResult r = RunDelibot(g, run.trace, &run.truth, s);
  omp_set_num_threads(2);
  test::ExpectSameRows(r, RunDelibot(g, run.trace, &run.truth, s));  // the audits too, at any thread count
  long passed = 0, refused = 0;
  for (const DelibotRow& row : r.rows) {
    passed += row.claim_audit == ClaimAuditOutcome::kPassed;
    refused += row.claim_audit == ClaimAuditOutcome::kRefused;
  }
  EXPECT_GE(passed, 1);
  EXPECT_EQ(r.summary.claims_refused, refused);
  EXPECT_GE(r.summary.standing_claim_iteration, 0);
  EXPECT_LT(r.summary.final_err_xy_m, 0.2);
}

TEST(ClaimAuditTest, RivalPlacesReachALookAlikeThatRanksBelowManyPlacesNearTheClaim) {
  const ClaimedPlace place{{0.0, 0.0, 0.0}, 1.0, 2.0 * kPi / 12};
  std::vector<Pose2> candidates;
  std::vector<double> totals;
  // Poses within the claimed place rank first; they are never rivals.
  for (int i = 0; i < 5; ++i) {
    candidates.push_back({0.1 * i, 0.0, 0.0});
    totals.push_back(10.0);
  }
  // 49 places near the claim (1.1 m apart, 1.5-8.1 m from it), each
  // fitting better than the far look-alike 30 m away, ranked last.
  for (int a = 0; a < 7; ++a)
    for (int b = 0; b < 7; ++b) {
      candidates.push_back({1.5 + 1.1 * a, 1.1 * b, 0.0});
      totals.push_back(5.0 - 0.01 * (7 * a + b));
    }
  const Pose2 look_alike{30.0, 0.0, 0.0};
  candidates.push_back(look_alike);
  totals.push_back(-1.0);
  const std::vector<Pose2> rivals = RivalPlaces(candidates, totals, place);
  ASSERT_GE(rivals.size(), kClaimAuditRivals);
  EXPECT_LE(rivals.size(), kClaimAuditRivals + kClaimAuditSpreadRivals);
  auto at = [](const Pose2& p, const Pose2& q) { return p.x == q.x && p.y == q.y; };
  // The best places are all near the claim; the spread places reach it.
  for (std::size_t r = 0; r < kClaimAuditRivals; ++r) EXPECT_FALSE(at(rivals[r], look_alike)) << r;
  EXPECT_TRUE(std::any_of(rivals.begin(), rivals.end(), [&](const Pose2& p) { return at(p, look_alike); }));
  for (const Pose2& r : rivals) EXPECT_GT(std::hypot(r.x, r.y), place.radius_m) << r.x << ", " << r.y;
  // Spread places are two bin radii from the claim and from each other.
  const std::vector<Pose2> spread(rivals.begin() + kClaimAuditRivals, rivals.end());
  for (std::size_t i = 0; i < spread.size(); ++i) {
    EXPECT_GT(std::hypot(spread[i].x, spread[i].y), 2.0 * place.radius_m);
    for (std::size_t j = 0; j < i; ++j)
      EXPECT_GT(std::hypot(spread[i].x - spread[j].x, spread[i].y - spread[j].y), 2.0 * place.radius_m);
  }
  EXPECT_THROW(RivalPlaces(candidates, {1.0}, place), std::invalid_argument);
}

TEST(ClaimAuditTest, TheLikelihoodFieldsBestSelectionIsAFullScoringsBestWithFewerQueries) {
  const OccupancyGrid g = test::AsymmetricRoom();
  const test::SyntheticRun run = test::DriveThrough(g, {{5.5, 3.0, 0}, {7.5, 3.0, 0}}, 0.05, 0.03, 3);
  const std::vector<Pose2> poses = UniformFreePoses(g, 200000, 12.0, 5);
  LikelihoodFieldParams edge;
  edge.unknown_is_edge = true;
  edge.combination = BeamCombination::kAmclCubeSum;  // selection scores the product whatever this is
  for (const LikelihoodFieldParams& params : {LikelihoodFieldParams{}, edge}) {
    LikelihoodFieldModel model(g, params);
    SensorUpdateWork work;
    std::vector<double> scores;
    model.SelectionLogLikelihoods(poses, run.trace.scans.back(), run.trace.geometry, BeamSelection{6}, scores, work);
    const std::uint64_t full_queries = work.rays;
    for (std::size_t keep : {std::size_t{1}, std::size_t{100}, std::size_t{20000}, poses.size() + 1}) {
      const std::vector<std::size_t> expected = BestIndices(scores, keep);
      for (int threads : {1, 2}) {
        omp_set_num_threads(threads);
        const std::vector<std::size_t> best =
            model.BestSelection(poses, run.trace.scans.back(), run.trace.geometry, BeamSelection{6}, keep, work);
        EXPECT_EQ(best, expected) << "keep " << keep << ", " << threads << " thread(s)";
        // Fewer queries where some poses cannot be among the best; a full
        // scoring where every pose is kept.
        if (keep < poses.size()) {
          EXPECT_LT(work.rays, full_queries) << "keep " << keep;
        } else {
          EXPECT_EQ(work.rays, full_queries);
        }
      }
    }
  }
}

TEST(ClaimAuditTest, NeedsAScan) {
  const OccupancyGrid g = test::AsymmetricRoom();
  LikelihoodFieldModel model(g, LikelihoodFieldParams{});
  RememberedRivals rivals;
  EXPECT_THROW(
      AuditClaim(
          model, g, {}, BeamSelection{6}, [] { return std::vector<Pose2>{}; }, ClaimedPlace{}, kWindowNats, rivals),
      std::invalid_argument);
}

}  // namespace
}  // namespace rc
