// Localization on the real CMU Wean Hall logs (../shared/data/wean), checked
// against a reference that does not come from the filter: the scan-matching
// trajectory of scripts/scan_match_reference.py (windows of 100 scans placed
// rigidly in the map by exhaustive correlation, chained by odometry). The
// checkpoint poses below are copied from its output; each is good to about
// 0.2 m (map cell plus odometry drift inside a window).
//
// What is pinned, and why:
// - Tracking from the reference start with the default beam model (recovery
//   off) stays within 1 m of the reference at every checkpoint of
//   robotdata1, 2 and 4 (on robotdata3 it drifts to about 1 m; docs/real_logs.md).
// - Global localization with the real-log recipe (likelihood field, 500,000
//   initial particles, no random injection) is within 1 m of the reference
//   at every checkpoint of the second half of robotdata2, 3 and 4, with
//   consistent scans, and without a jump after convergence on robotdata2
//   (on robotdata3 the ground-truth-free convergence comes while two doors
//   are still alive, and the estimate jumps between them before settling).
// - With hypothesis-preserving resampling (a 500-particle floor) the
//   recipe's own (ground-truth-free) claim of convergence comes in the first
//   half of every log and holds at every later checkpoint.
// - Every beam at beam step 1 keeps every weight finite on all four logs.
// robotdata1 is left out of the recipe's global check: two of three seeds
// lock onto the door 6 m west of the truth (docs/real_logs.md); with nav2's update gating, its cube-sum likelihood or
// the hypothesis floor it localizes, and that is checked.
#include <algorithm>
#include <cmath>
#include <ostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "maps/map_loader.h"
#include "real_log_recipes.h"
#include "support/sanitizer_build.h"
#include "support/test_data.h"
#include "traces/trace_reader.h"
#include "workloads/delibot/delibot_defaults.h"
#include "workloads/delibot/delibot_run.h"

namespace rc {
namespace {

struct Checkpoint {
  long record;
  Pose2 reference;
};

struct RealLog {
  std::string name;
  std::vector<Checkpoint> checkpoints;  // from out/reference/<name>.ref.txt
};

std::string PrintName(const ::testing::TestParamInfo<RealLog>& info) { return info.param.name; }

// How GoogleTest (and so CTest's test list) prints a parameter: its name,
// not the struct's bytes.
void PrintTo(const RealLog& log, std::ostream* os) { *os << log.name; }

const RealLog kRobotdata1{"robotdata1",
                          {{0, {40.016, 41.471, -1.658}},
                           {150, {47.109, 39.311, -0.039}},
                           {300, {48.136, 38.798, 3.126}},
                           {450, {38.181, 39.814, 3.002}},
                           {600, {33.635, 40.516, 0.211}},
                           {712, {39.810, 41.448, 1.316}}}};
const RealLog kRobotdata2{"robotdata2",
                          {{0, {40.031, 41.413, -1.636}},
                           {300, {30.140, 41.291, 3.009}},
                           {600, {17.204, 42.540, 3.042}},
                           {900, {23.690, 41.256, 0.074}},
                           {1200, {36.422, 40.033, -0.046}},
                           {1500, {49.114, 39.032, -0.012}},
                           {1800, {54.484, 39.002, -2.928}},
                           {2100, {41.853, 39.531, -3.138}},
                           {2250, {40.183, 42.424, 1.310}}}};
const RealLog kRobotdata3{"robotdata3",
                          {{0, {39.937, 41.565, -1.759}},
                           {300, {46.097, 39.381, -0.277}},
                           {600, {37.847, 40.043, 2.901}},
                           {900, {30.166, 41.113, -2.804}},
                           {1200, {39.208, 39.899, -0.017}},
                           {1240, {39.616, 39.889, -0.099}}}};
const RealLog kRobotdata4{"robotdata4",
                          {{0, {46.363, 39.648, -1.611}},
                           {150, {51.401, 38.948, -0.316}},
                           {300, {50.418, 39.447, 2.878}},
                           {450, {44.179, 39.912, 3.094}},
                           {599, {39.840, 41.135, 1.402}}}};

struct WeanInputs {
  LoadedMap map;
  SensorTrace trace;
};

WeanInputs Load(const std::string& log) {
  TraceReadOptions options;
  return {LoadMap(test::SharedDataPath("wean/wean.dat")),
          ReadTrace(test::SharedDataPath("wean/" + log + ".log"), options)};
}

double PositionError(const DelibotRow& row, const Pose2& reference) {
  return std::hypot(row.estimate.x - reference.x, row.estimate.y - reference.y);
}

// The logs a parameterized suite checks: the given ones in a Release build;
// in a sanitizer build only robotdata4, the shortest, which every suite
// includes (tests/support/sanitizer_build.h).
std::vector<RealLog> LogsToCheck(const std::vector<RealLog>& logs) {
  if (!test::kSanitizerBuild) return logs;
  std::vector<RealLog> shortest;
  for (const RealLog& log : logs)
    if (log.name == "robotdata4") shortest.push_back(log);
  return shortest;
}

class RealLogTracking : public ::testing::TestWithParam<RealLog> {};

TEST_P(RealLogTracking, BeamModelFollowsTheScanMatchingReference) {
  RC_REQUIRE_SHARED_DATA("wean/" + GetParam().name + ".log");
  const WeanInputs in = Load(GetParam().name);
  DelibotSettings s;
  s.mcl.particle_count = 500;
  s.mcl.alpha_slow = 0.0;  // injection makes a tracked filter jump to look-alike corridors
  s.initial_pose = GetParam().checkpoints.front().reference;
  const DelibotResult r = RunDelibot(in.map.grid, in.trace, nullptr, s);
  ASSERT_EQ(r.rows.size(), in.trace.scans.size());
  EXPECT_FALSE(r.summary.any_non_finite_weight);
  for (const Checkpoint& c : GetParam().checkpoints)
    EXPECT_LT(PositionError(r.rows[c.record], c.reference), 1.0) << "record " << c.record;
}

INSTANTIATE_TEST_SUITE_P(Wean, RealLogTracking,
                         ::testing::ValuesIn(LogsToCheck({kRobotdata1, kRobotdata2, kRobotdata4})), PrintName);

using test::RealLogRecipe;

// Global localization: converged, consistent, finite, and within 1 m of the
// reference at every checkpoint of the log's second half. The first half may
// still hold two look-alike doors 6 m apart (the estimate then switches
// between them); by the second half it must not.
void ExpectLocalizedThroughTheSecondHalf(const DelibotResult& r, const RealLog& log) {
  EXPECT_FALSE(r.summary.any_non_finite_weight);
  EXPECT_GE(r.summary.convergence_iteration, 0);
  EXPECT_GE(r.summary.median_consistency, 0.75);
  const long half = static_cast<long>(r.rows.size()) / 2;
  for (const Checkpoint& c : log.checkpoints)
    if (c.record >= half) {
      EXPECT_LT(PositionError(r.rows[c.record], c.reference), 1.0) << log.name << " record " << c.record;
    }
}

class RealLogGlobalLocalization : public ::testing::TestWithParam<RealLog> {};

TEST_P(RealLogGlobalLocalization, LikelihoodFieldRecipeEndsAtTheReference) {
  RC_REQUIRE_SHARED_DATA("wean/" + GetParam().name + ".log");
  const WeanInputs in = Load(GetParam().name);
  const DelibotResult r = RunDelibot(in.map.grid, in.trace, nullptr, RealLogRecipe());
  ExpectLocalizedThroughTheSecondHalf(r, GetParam());
  if (GetParam().name == "robotdata2") {
    EXPECT_EQ(r.summary.jumps_after_convergence, 0);
  }
}

INSTANTIATE_TEST_SUITE_P(Wean, RealLogGlobalLocalization,
                         ::testing::ValuesIn(LogsToCheck({kRobotdata2, kRobotdata3, kRobotdata4})), PrintName);

// With nav2's update gating the recipe also localizes robotdata1 (3 of 3
// seeds), at the price of robotdata2 (1 of 3; docs/real_logs.md).
TEST(RealLogGlobalLocalization, GatedRecipeLocalizesRobotdata1) {
  RC_REQUIRE_SHARED_DATA("wean/robotdata1.log");
  const WeanInputs in = Load("robotdata1");
  DelibotSettings s = RealLogRecipe();
  s.mcl.update_min_d_m = 0.25;
  s.mcl.update_min_a_rad = 0.2;
  const DelibotResult r = RunDelibot(in.map.grid, in.trace, nullptr, s);
  ExpectLocalizedThroughTheSecondHalf(r, kRobotdata1);
}

// nav2 AMCL's flat cube-sum combination (after the product picks the
// working set out of the dense first set) keeps the true door of robotdata1
// alive where the product loses it (3 of 3 seeds against 1 of 3; docs/real_logs.md).
TEST(RealLogGlobalLocalization, CubeSumRecipeLocalizesRobotdata1) {
  RC_RELEASE_ONLY("BeamModelTest.AmclCubeSumMatchesNav2sFormula and the recipe's other real-log tests");
  RC_REQUIRE_SHARED_DATA("wean/robotdata1.log");
  const WeanInputs in = Load("robotdata1");
  DelibotSettings s = RealLogRecipe();
  s.likelihood.combination = BeamCombination::kAmclCubeSum;
  const DelibotResult r = RunDelibot(in.map.grid, in.trace, nullptr, s);
  ExpectLocalizedThroughTheSecondHalf(r, kRobotdata1);
  // The product (the recipe) with this seed settles one door west.
  const DelibotResult product = RunDelibot(in.map.grid, in.trace, nullptr, RealLogRecipe());
  EXPECT_GT(PositionError(product.rows.back(), kRobotdata1.checkpoints.back().reference), 3.0);
}

// Hypothesis-preserving resampling keeps robotdata1's true door alive
// through the first 150 records, where the door 6 m west fits the scans a
// few nats better, until the scans decide for it (by 100 nats at record 150
// and 950 at the end); the plain recipe on the same seed loses it (checked
// above). And while a rival hypothesis is alive the filter does not claim
// convergence, so on robotdata3, where the plain recipe claims while two
// doors are alive and then switches, its claim comes later and holds. On
// robotdata2 the true track trails the look-alikes along the corridor
// (records 180-500) and survives because the floor holds 500 particles: a
// hypothesis held by 20 loses about 0.5 nats per update to sampling alone
// (scripts/evidence_vs_particles.py), and was lost in 2 of 3 seeds.
// Checked on all four logs: the claim comes in the first half of the log,
// with rivals counted on the way, and from the claim on every checkpoint is
// within 1 m of the reference (seed 1; docs/real_logs_particles.md: 37 of 40
// runs over 10 seeds).
class RealLogHypothesisFloor : public ::testing::TestWithParam<RealLog> {};

TEST_P(RealLogHypothesisFloor, OwnClaimOfConvergenceHolds) {
  RC_REQUIRE_SHARED_DATA("wean/" + GetParam().name + ".log");
  const WeanInputs in = Load(GetParam().name);
  DelibotSettings s = RealLogRecipe();
  s.mcl.hypothesis_floor.min_particles = 500;
  const DelibotResult r = RunDelibot(in.map.grid, in.trace, nullptr, s);
  EXPECT_FALSE(r.summary.any_non_finite_weight);
  const long claim = r.summary.convergence_iteration;
  ASSERT_GE(claim, 0);
  EXPECT_LT(claim, static_cast<long>(r.rows.size()) / 2);
  // The claim waited for rivals: one was alive at some update before it.
  int most_alive_before_claim = 0;
  for (long k = 0; k < claim; ++k)
    most_alive_before_claim = std::max(most_alive_before_claim, r.rows[k].hypotheses_alive);
  EXPECT_GT(most_alive_before_claim, 1);
  for (const Checkpoint& c : GetParam().checkpoints)
    if (c.record >= claim) {
      EXPECT_LT(PositionError(r.rows[c.record], c.reference), 1.0) << GetParam().name << " record " << c.record;
    }
}

INSTANTIATE_TEST_SUITE_P(Wean, RealLogHypothesisFloor,
                         ::testing::ValuesIn(LogsToCheck({kRobotdata1, kRobotdata2, kRobotdata3, kRobotdata4})),
                         PrintName);

// At a fixed size the floor holds only particle_count / (2 * floor)
// hypotheses: at robotdata1's second update 17 places are within 21 nats,
// 2000 particles with a 500 floor keep the heaviest two, and with seed 4 the
// true place is not one of them. Letting the set grow to 20000 while rivals
// are alive keeps it, and the set is back at 2000 by the claim (10 of 10
// seeds on robotdata1, 3 and 4; docs/real_logs_particles.md).
TEST(RealLogGrowingSet, KeepsTheTruePlaceThatAFixedSizeDrops) {
  RC_RELEASE_ONLY("ParticleSetGrowthTest and RealLogHypothesisFloor (the same recipe and floor)");
  RC_REQUIRE_SHARED_DATA("wean/robotdata1.log");
  const WeanInputs in = Load("robotdata1");
  DelibotSettings s = RealLogRecipe();
  s.mcl.hypothesis_floor.min_particles = 500;
  s.mcl.seed = 4;
  const DelibotResult fixed = RunDelibot(in.map.grid, in.trace, nullptr, s);
  EXPECT_GT(PositionError(fixed.rows.back(), kRobotdata1.checkpoints.back().reference), 3.0);
  s.mcl.max_particle_count = 20000;
  const DelibotResult r = RunDelibot(in.map.grid, in.trace, nullptr, s);
  EXPECT_FALSE(r.summary.any_non_finite_weight);
  std::size_t largest = 0;
  for (const DelibotRow& row : r.rows) largest = std::max(largest, row.particles);
  EXPECT_GT(largest, 10000u);
  const long claim = r.summary.convergence_iteration;
  ASSERT_GE(claim, 0);
  EXPECT_LT(claim, static_cast<long>(r.rows.size()) / 2);
  EXPECT_EQ(r.rows[static_cast<std::size_t>(claim)].particles, 2000u);
  for (const Checkpoint& c : kRobotdata1.checkpoints)
    if (c.record >= claim) {
      EXPECT_LT(PositionError(r.rows[c.record], c.reference), 1.0) << "record " << c.record;
    }
}

// The cautious recipe (real_log_recipes.h). On every log the run ends
// within 0.3 m of the reference, the filter claims convergence, and every
// checkpoint from the claim on is within 1 m. robotdata2 claims only after
// record 1260, where the scans first decide against the look-alike 12 m
// east. (With an 8-nat window robotdata3 left its rival inside the window
// in 4 of 10 seeds and never claimed; docs/real_logs_cautious_recipe.md.)
class RealLogCautiousRecipe : public ::testing::TestWithParam<RealLog> {};

TEST_P(RealLogCautiousRecipe, EveryRunClaimsAndEveryClaimHolds) {
  RC_REQUIRE_SHARED_DATA("wean/" + GetParam().name + ".log");
  const WeanInputs in = Load(GetParam().name);
  const DelibotSettings s = test::CautiousRealLogRecipe();
  const DelibotResult r = RunDelibot(in.map.grid, in.trace, nullptr, s);
  EXPECT_FALSE(r.summary.any_non_finite_weight);
  EXPECT_LT(PositionError(r.rows.back(), GetParam().checkpoints.back().reference), 0.3);
  const long claim = r.summary.convergence_iteration;
  ASSERT_GE(claim, 0);
  EXPECT_EQ(r.summary.claims_withdrawn, 0);
  EXPECT_EQ(r.summary.standing_claim_iteration, claim);
  if (GetParam().name == "robotdata2") {
    EXPECT_GT(claim, 1260);
  }
  for (const Checkpoint& c : GetParam().checkpoints)
    if (c.record >= claim) {
      EXPECT_LT(PositionError(r.rows[c.record], c.reference), 1.0) << GetParam().name << " record " << c.record;
    }
}

INSTANTIATE_TEST_SUITE_P(Wean, RealLogCautiousRecipe,
                         ::testing::ValuesIn(LogsToCheck({kRobotdata1, kRobotdata2, kRobotdata3, kRobotdata4})),
                         PrintName);

// rcbench's defaults (docs/defaults.md): the likelihood field while rivals
// are alive, then the beam model. Checked where each stage matters:
// robotdata3, where the beam model's product drifts 1.2 m from the
// reference while tracking and the cube sum the defaults use does not, and
// robotdata4, the shortest log. Seed 1: a claim, never withdrawn, the
// beam model tracking from the hand-over on (ray casts: several nodes per
// query), every checkpoint from the hand-over on within 1 m, and the end
// within 0.3 m of the reference. The claim audit makes the claim late
// (records 1158 of 1241 and 536 of 600): Wean's corridors look alike over
// a few scans, and a claim is made only once its scans single out its
// place. The audit does not steer the filter, so the hand-over comes as
// early as without it.
class RealLogDefaultSettings : public ::testing::TestWithParam<RealLog> {};

TEST_P(RealLogDefaultSettings, ClaimsOnlyWhatHoldsAndTracksWithTheBeamModel) {
  RC_REQUIRE_SHARED_DATA("wean/" + GetParam().name + ".log");
  const WeanInputs in = Load(GetParam().name);
  const DelibotResult r = RunDelibot(in.map.grid, in.trace, nullptr, DefaultDelibotSettings());
  EXPECT_FALSE(r.summary.any_non_finite_weight);
  const long claim = r.summary.convergence_iteration;
  ASSERT_GE(claim, 0);
  EXPECT_EQ(r.summary.claims_withdrawn, 0);
  EXPECT_EQ(r.summary.standing_claim_iteration, claim);
  long hand_over = -1;
  for (const DelibotRow& row : r.rows)
    if (row.tracking_stage) {
      hand_over = row.iteration;
      break;
    }
  ASSERT_GE(hand_over, 0);
  EXPECT_LE(hand_over, claim + 10);
  for (const Checkpoint& c : GetParam().checkpoints)
    if (c.record >= std::min(hand_over, claim)) {
      EXPECT_LT(PositionError(r.rows[c.record], c.reference), 1.0) << GetParam().name << " record " << c.record;
    }
  // Once handed over, the beam model tracks: at most 10 updates of the
  // global model after the claim.
  int global_updates_after_claim = 0;
  for (const DelibotRow& row : r.rows)
    if (row.iteration >= claim && row.sensor_updated) {
      if (!row.tracking_stage) {
        ++global_updates_after_claim;
        continue;
      }
      ASSERT_GT(row.NodesPerRay(), 1.5) << "record " << row.iteration;
    }
  EXPECT_LE(global_updates_after_claim, 10);
  EXPECT_LT(PositionError(r.rows.back(), GetParam().checkpoints.back().reference), 0.3);
}

INSTANTIATE_TEST_SUITE_P(Wean, RealLogDefaultSettings, ::testing::ValuesIn(LogsToCheck({kRobotdata3, kRobotdata4})),
                         PrintName);

// The plain filter (DelibotSettings' own member defaults, and rcbench's
// defaults before docs/defaults.md: beam model, 2000 particles, recovery on)
// does not localize the real logs (docs/real_logs.md). Its first claim comes within 20
// records, but the filter later contradicts it (jumps, injected particles),
// so no claim stands at the end and the run does not report itself
// localized.
TEST(RealLogPlainFilter, NoClaimStandsWhereThePlainFilterIsLost) {
  RC_RELEASE_ONLY("RealLogEveryBeam (the plain filter's settings, all four logs, 150 records each)");
  RC_REQUIRE_SHARED_DATA("wean/robotdata1.log");
  const WeanInputs in = Load("robotdata1");
  const DelibotResult r = RunDelibot(in.map.grid, in.trace, nullptr, DelibotSettings{});
  EXPECT_GT(PositionError(r.rows.back(), kRobotdata1.checkpoints.back().reference), 5.0);
  EXPECT_GE(r.summary.self_convergence_iteration, 0);
  EXPECT_GT(r.summary.claims_withdrawn, 0);
  EXPECT_EQ(r.summary.standing_claim_iteration, -1);
  EXPECT_FALSE(r.summary.converged);
}

class RealLogEveryBeam : public ::testing::TestWithParam<std::string> {};

TEST_P(RealLogEveryBeam, AllBeamsKeepEveryWeightFinite) {
  // 180 beams per scan: a log-likelihood sum 6x longer than the default's,
  // over the first 150 records (people, max readings and the start-up pause).
  RC_REQUIRE_SHARED_DATA("wean/" + GetParam() + ".log");
  const WeanInputs in = Load(GetParam());
  DelibotSettings s;
  s.mcl.particle_count = 300;
  s.mcl.beams.beam_step = 1;
  s.max_records = 150;
  const DelibotResult r = RunDelibot(in.map.grid, in.trace, nullptr, s);
  EXPECT_FALSE(r.summary.any_non_finite_weight);
  for (const DelibotRow& row : r.rows) {
    ASSERT_TRUE(std::isfinite(row.ess) && row.ess >= 1.0 - 1e-9) << "record " << row.iteration;
    ASSERT_TRUE(std::isfinite(row.estimate.x) && std::isfinite(row.estimate.theta)) << row.iteration;
  }
}

INSTANTIATE_TEST_SUITE_P(Wean, RealLogEveryBeam,
                         ::testing::Values("robotdata1", "robotdata2", "robotdata3", "robotdata4"));

}  // namespace
}  // namespace rc
