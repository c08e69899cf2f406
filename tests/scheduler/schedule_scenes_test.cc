// The scheduler's decisions pinned on two generated scenes (issue #20 §5):
//   hall    the 60 m x 40 m open hall (maps/hall_map_generator.h), global
//           localization from 10,000 uniform particles, max range 40 m: the
//           paper's regime, in which long rays come early;
//   office  the 20 m x 15 m office, tracking from the true start pose, max
//           range 10 m: short rays throughout.
// For each ray caster the test pins the iterations at which the adaptive
// policy switched and those at which the hindsight oracle's choice changed
// (over all backends), that the policy starts on the oracle's backend, that
// it ends within 2% of the oracle, and the paper's pair {simt, robocore}:
// which one the oracle over that pair chooses on each update, summarised as
// the range of the per-update cycle ratio simt / robocore. A model or policy
// change that moves a decision fails here; regenerate the pinned values
// deliberately (the failure message prints them) and say why in the commit.
// The study these scenes come from is docs/scheduling.md ("Scenes").
#include <algorithm>
#include <cstddef>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "backends/scheduler/backend_scheduler.h"
#include "maps/hall_map_generator.h"
#include "maps/office_map_generator.h"
#include "support/sanitizer_build.h"
#include "workloads/delibot/delibot_run.h"
#include "workloads/delibot/trace_simulator.h"

namespace rc {
namespace {

struct SceneDecisions {
  std::vector<int> adaptive_switches;       // iterations at which adaptive switched
  std::vector<int> oracle_changes;          // priced iterations at which the oracle's choice changed
  int simt_wins = 0, robocore_wins = 0;     // updates on which each is cheaper (the pair's oracle, no switch cost)
  double min_ratio = 0.0, max_ratio = 0.0;  // simt / robocore cycles per update
};

std::string Show(const std::vector<int>& v) {
  std::string s = "{";
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + std::to_string(v[i]);
  return s + "}";
}

SceneDecisions Decide(const DelibotResult& r) {
  SceneDecisions d;
  const LedgerSummary& l = r.pricing;
  const auto index = [&](const char* name) {
    return static_cast<std::size_t>(std::find(l.backends.begin(), l.backends.end(), name) - l.backends.begin());
  };
  const std::size_t simt = index("simt"), robocore = index("robocore");
  std::string last_oracle;
  d.min_ratio = 1e300;
  for (std::size_t i = 0; i < r.rows.size(); ++i) {
    const LedgerIteration& p = r.rows[i].pricing;
    if (p.switched) d.adaptive_switches.push_back(static_cast<int>(i));
    if (!p.priced) continue;
    if (!last_oracle.empty() && l.oracle_choice[i] != last_oracle) d.oracle_changes.push_back(static_cast<int>(i));
    last_oracle = l.oracle_choice[i];
    const double ratio = static_cast<double>(p.costs[simt].cycles) / static_cast<double>(p.costs[robocore].cycles);
    d.min_ratio = std::min(d.min_ratio, ratio);
    d.max_ratio = std::max(d.max_ratio, ratio);
    (ratio < 1.0 ? d.simt_wins : d.robocore_wins) += 1;
  }
  return d;
}

DelibotSettings SceneSettings(RayCastMethod caster) {
  DelibotSettings s;
  s.mcl.particle_count = 300;
  s.mcl.seed = 5;
  s.ray_caster = caster;
  s.price_backends = true;
  s.ledger.policy.kind = SchedulerKind::kAdaptive;
  return s;
}

struct Expected {
  RayCastMethod caster;
  std::vector<int> adaptive_switches, oracle_changes;
  int simt_wins, robocore_wins;
};

// Issue #20's acceptance: within 2% of the oracle.
constexpr double kMaxGapPercent = 2.0;

void ExpectDecisions(const DelibotResult& r, const Expected& e, const std::string& scene) {
  ASSERT_TRUE(r.priced);
  const SceneDecisions d = Decide(r);
  const std::string what = scene + " " + ToString(e.caster);
  EXPECT_EQ(d.adaptive_switches, e.adaptive_switches) << what << ": adaptive switched at " << Show(d.adaptive_switches);
  EXPECT_EQ(d.oracle_changes, e.oracle_changes) << what << ": the oracle changed at " << Show(d.oracle_changes);
  EXPECT_EQ(d.simt_wins, e.simt_wins) << what << ": simt/robocore per update in [" << d.min_ratio << ", " << d.max_ratio
                                      << "]";
  EXPECT_EQ(d.robocore_wins, e.robocore_wins) << what;
  // Where the policy starts (nothing measured yet): on these scenes the
  // start probe picks the oracle's backend for the first priced update.
  const auto first =
      std::find_if(r.rows.begin(), r.rows.end(), [](const DelibotRow& row) { return row.pricing.priced; });
  ASSERT_NE(first, r.rows.end()) << what;
  EXPECT_EQ(first->pricing.backend, r.pricing.oracle_choice[static_cast<std::size_t>(first - r.rows.begin())]) << what;
  EXPECT_LE(r.pricing.gap_to_oracle_percent, kMaxGapPercent) << what;
  EXPECT_EQ(r.pricing.oracle_lasting_changes_followed, r.pricing.oracle_lasting_changes) << what;
}

TEST(ScheduleScenesTest, OpenHallGlobalLocalizationLongRaysEarly) {
  const OccupancyGrid grid = GenerateHallMap(HallMapOptions{});
  SimulationOptions sim;
  sim.seed = 2;
  sim.record_count = 40;
  sim.geometry.max_range_m = 40.0;
  const SimulatedTrace trace = SimulateTrace(grid, sim);
  const std::vector<Expected> expected = {
      {RayCastMethod::kMarch, {2}, {1}, 0, 27},
      {RayCastMethod::kDda, {2, 4}, {1, 3}, 26, 1},
      {RayCastMethod::kRayMarching, {2}, {1}, 0, 27},
  };
  // A sanitizer build checks march only (tests/support/sanitizer_build.h).
  const std::size_t casters = test::FullOrUnderSanitizer(expected.size(), std::size_t{1});
  for (std::size_t i = 0; i < casters; ++i) {
    const Expected& e = expected[i];
    DelibotSettings s = SceneSettings(e.caster);
    s.mcl.initial_particle_count = 10000;
    s.beam.max_range_m = 40.0;
    // The first update (10,000 particles) holds about 90% of the run's
    // cycles, and the policy picks its backend before any counter exists,
    // from a start probe (workloads/delibot/start_probe.h); a near-tie
    // missed there is the whole gap (march: TTA+-cr for TTA+ is 2.5% dearer
    // on that update, and the spread probe that picked it left the run 2.3%
    // above the oracle).
    ExpectDecisions(RunDelibot(grid, trace.trace, nullptr, s), e, "hall");
  }
}

TEST(ScheduleScenesTest, OfficeTrackingShortRays) {
  const OccupancyGrid grid = GenerateOfficeMap(OfficeMapOptions{});
  SimulationOptions sim;
  sim.seed = 3;
  sim.record_count = 40;
  const SimulatedTrace trace = SimulateTrace(grid, sim);
  const std::vector<Expected> expected = {
      {RayCastMethod::kMarch, {}, {}, 0, 32},
      {RayCastMethod::kDda, {}, {}, 32, 0},
      {RayCastMethod::kRayMarching, {}, {}, 0, 32},
  };
  for (const Expected& e : expected) {
    DelibotSettings s = SceneSettings(e.caster);
    s.initial_pose = trace.ground_truth.front().pose;
    ExpectDecisions(RunDelibot(grid, trace.trace, nullptr, s), e, "office");
  }
}

}  // namespace
}  // namespace rc
