// Regression tests of the adaptive policy on DeliBot runs with fixed seeds:
// on the real Wean logs (when ../shared/data is present) and on a simulated
// trace, adaptive is graded as issue #20's acceptance asks: within 2% of the
// hindsight oracle's total, the oracle's choice (or one within 1% of its
// cycles: LedgerSummary::kEquivalentPercent) in at least 90% of priced
// updates, and every lasting change of the oracle's choice followed. (An
// online policy that pays for switches cannot promise to stay at or below
// the best static backend's total on every run: a one-update spike it
// follows costs it the switch back.)
#include <algorithm>
#include <string>

#include <gtest/gtest.h>

#include "maps/cmu_map_loader.h"
#include "maps/office_map_generator.h"
#include "support/test_data.h"
#include "traces/trace_reader.h"
#include "workloads/delibot/delibot_run.h"
#include "workloads/delibot/trace_simulator.h"

namespace rc {
namespace {

DelibotSettings PricedSettings() {
  DelibotSettings s;
  s.mcl.particle_count = 300;
  s.mcl.seed = 11;
  s.max_records = 60;
  s.price_backends = true;
  s.ledger.policy.kind = SchedulerKind::kAdaptive;
  return s;
}

void ExpectAdaptiveGrades(const DelibotResult& r, const std::string& what) {
  ASSERT_TRUE(r.priced) << what;
  const LedgerSummary& l = r.pricing;
  const double best_static = *std::min_element(l.static_total_cycles.begin(), l.static_total_cycles.end());
  EXPECT_GT(best_static, 0.0) << what;
  EXPECT_LE(l.policy_total_cycles, 1.02 * best_static) << what;
  EXPECT_LE(l.gap_to_oracle_percent, 2.0) << what;
  EXPECT_GE(l.oracle_equivalent_percent, 90.0) << what << " (exact agreement " << l.oracle_agreement_percent << "%)";
  EXPECT_EQ(l.oracle_lasting_changes_followed, l.oracle_lasting_changes) << what;
  EXPECT_GE(l.policy_total_cycles, l.oracle_total_cycles) << what << ": nothing beats hindsight";
}

TEST(DelibotScheduleTest, AdaptiveOnTheRealWeanLogs) {
  RC_REQUIRE_SHARED_DATA("wean/robotdata1.log");
  const OccupancyGrid grid = LoadCmuMap(test::SharedDataPath("wean/wean.dat"));
  for (int log = 1; log <= 4; ++log) {
    const std::string name = "wean/robotdata" + std::to_string(log) + ".log";
    const SensorTrace trace = ReadTrace(test::SharedDataPath(name), TraceReadOptions{});
    ExpectAdaptiveGrades(RunDelibot(grid, trace, nullptr, PricedSettings()), name);
  }
}

TEST(DelibotScheduleTest, AdaptiveOnASimulatedTrace) {
  const OccupancyGrid grid = GenerateOfficeMap(OfficeMapOptions{});
  SimulationOptions sim;
  sim.record_count = 80;
  const SimulatedTrace trace = SimulateTrace(grid, sim);
  for (auto caster : {RayCastMethod::kMarch, RayCastMethod::kDda, RayCastMethod::kRayMarching}) {
    DelibotSettings s = PricedSettings();
    s.ray_caster = caster;
    ExpectAdaptiveGrades(RunDelibot(grid, trace.trace, nullptr, s), ToString(caster));
  }
}

// The injection check replays recent scans for every random pose; those
// casts run on the device too, so the ledger must price exactly the queries
// the timeline reports, update and check together.
TEST(DelibotScheduleTest, InjectionCheckCastsArePriced) {
  const OccupancyGrid grid = GenerateOfficeMap(OfficeMapOptions{});
  SimulationOptions sim;
  sim.record_count = 120;
  sim.kidnap_record = 40;  // makes augmented MCL inject, so the check runs
  const SimulatedTrace trace = SimulateTrace(grid, sim);
  DelibotSettings s = PricedSettings();
  s.max_records = 120;
  s.mcl.injection_check_updates = 10;
  const DelibotResult r = RunDelibot(grid, trace.trace, nullptr, s);
  ASSERT_TRUE(r.priced);
  const std::uint64_t update_rays =
      static_cast<std::uint64_t>(s.mcl.particle_count) * s.mcl.beams.Count(trace.trace.geometry.beam_count);
  int checked_rows = 0;
  for (const DelibotRow& row : r.rows) {
    if (row.rays == 0) continue;
    ASSERT_TRUE(row.pricing.priced) << "record " << row.iteration;
    EXPECT_NEAR(row.pricing.nodes_per_query, static_cast<double>(row.nodes) / row.rays, 1e-9)
        << "record " << row.iteration;
    if (row.injected + row.injection_rejected > 0) {
      ++checked_rows;
      EXPECT_GT(row.rays, update_rays) << "record " << row.iteration;
    }
  }
  EXPECT_GT(checked_rows, 0) << "no random pose was drawn: the scenario no longer exercises the check";
}

}  // namespace
}  // namespace rc
