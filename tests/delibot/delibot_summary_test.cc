// The run summary's ground-truth-free verdicts, on hand-made timelines: when
// a run counts as converged, whether it still is at the end, and the
// last-updates medians that say why not (a split belief, or scans that
// disagree with the map).
#include <gtest/gtest.h>

#include "workloads/delibot/delibot_run.h"

namespace rc {
namespace {

DelibotRow Row(long iteration, bool sensor_updated, double mode_weight, double consistency) {
  DelibotRow r;
  r.iteration = iteration;
  r.sensor_updated = sensor_updated;
  r.mode_weight = mode_weight;
  r.consistency = consistency;
  return r;
}

// 20 good sensor updates, then `tail` as given.
std::vector<DelibotRow> GoodThen(const std::vector<std::pair<double, double>>& tail) {
  std::vector<DelibotRow> rows;
  for (long k = 0; k < 20; ++k) rows.push_back(Row(k, true, 0.95, 0.9));
  for (const auto& [mode, cons] : tail) rows.push_back(Row(static_cast<long>(rows.size()), true, mode, cons));
  return rows;
}

TEST(DelibotSummaryTest, EndMediansSayWhyTheEndIsNotConfirmed) {
  const DelibotSettings s;
  // Scans disagree with the map at the end: confident, inconsistent.
  const DelibotSummary map_disagrees =
      SummarizeDelibot(GoodThen(std::vector<std::pair<double, double>>(10, {1.0, 0.4})), s);
  EXPECT_EQ(map_disagrees.convergence_iteration, 0);
  EXPECT_FALSE(map_disagrees.converged);
  EXPECT_DOUBLE_EQ(map_disagrees.end_mode_weight, 1.0);
  EXPECT_DOUBLE_EQ(map_disagrees.end_consistency, 0.4);
  // A split belief: consistent at the mode, but the mode holds half the weight.
  const DelibotSummary split = SummarizeDelibot(GoodThen(std::vector<std::pair<double, double>>(10, {0.5, 0.9})), s);
  EXPECT_FALSE(split.converged);
  EXPECT_DOUBLE_EQ(split.end_mode_weight, 0.5);
  EXPECT_DOUBLE_EQ(split.end_consistency, 0.9);
  // Four bad updates among the last ten: most pass, still localized; the
  // medians come from the last ten sensor updates only.
  std::vector<std::pair<double, double>> mixed(6, {0.9, 0.8});
  for (int k = 0; k < 4; ++k) mixed.push_back({0.9, 0.1});
  const DelibotSummary mostly = SummarizeDelibot(GoodThen(mixed), s);
  EXPECT_TRUE(mostly.converged);
  EXPECT_DOUBLE_EQ(mostly.end_consistency, 0.8);
}

TEST(DelibotSummaryTest, NoClaimWhileARivalHypothesisIsAlive) {
  const DelibotSettings s;
  // Confident and consistent from the start, but a second hypothesis stays
  // within the floor's window for the first 15 updates: the claim waits.
  std::vector<DelibotRow> rows = GoodThen(std::vector<std::pair<double, double>>(20, {0.95, 0.9}));
  for (DelibotRow& r : rows) r.hypotheses_alive = r.iteration < 15 ? 2 : 1;
  EXPECT_EQ(SummarizeDelibot(rows, s).convergence_iteration, 15);
  // Without the floor the count is 0 (not computed) and does not block.
  for (DelibotRow& r : rows) r.hypotheses_alive = 0;
  EXPECT_EQ(SummarizeDelibot(rows, s).convergence_iteration, 0);
  // With ground truth, convergence is judged against the truth, and the
  // filter's own claim is reported beside it.
  for (DelibotRow& r : rows) {
    r.has_ground_truth = true;
    r.err_xy_m = r.iteration < 5 ? 1.0 : 0.05;
    r.hypotheses_alive = r.iteration < 12 ? 3 : 1;
  }
  const DelibotSummary judged = SummarizeDelibot(rows, s);
  EXPECT_EQ(judged.convergence_iteration, 5);
  EXPECT_EQ(judged.self_convergence_iteration, 12);
}

// A claim stands until the filter contradicts it: a jump of the estimate or
// injected random particles after it withdraw it, and the claim standing at
// the end needs 10 more localized updates. A dip in consistency breaks a
// run being built but withdraws nothing.
TEST(DelibotSummaryTest, AJumpOrAnInjectionAfterAClaimWithdrawsIt) {
  const DelibotSettings s;
  std::vector<DelibotRow> rows = GoodThen(std::vector<std::pair<double, double>>(40, {0.95, 0.9}));
  const DelibotSummary clean = SummarizeDelibot(rows, s);
  EXPECT_EQ(clean.standing_claim_iteration, 0);
  EXPECT_EQ(clean.claims_withdrawn, 0);
  // Claimed at 0; at record 25 the estimate jumps 3 m (and stays there).
  for (DelibotRow& r : rows) r.estimate.x = r.iteration >= 25 ? 3.0 : 0.0;
  const DelibotSummary jumped = SummarizeDelibot(rows, s);
  EXPECT_EQ(jumped.self_convergence_iteration, 0);
  EXPECT_EQ(jumped.claims_withdrawn, 1);
  EXPECT_EQ(jumped.standing_claim_iteration, 25);
  EXPECT_TRUE(jumped.converged);
  // Then particles injected at record 50: withdrawn again; with only 10
  // updates left (50-59) the new claim is made on the last of them.
  rows[50].injected = 30;
  const DelibotSummary injected = SummarizeDelibot(rows, s);
  EXPECT_EQ(injected.claims_withdrawn, 2);
  EXPECT_EQ(injected.standing_claim_iteration, 50);
  // Injected at 55: no claim stands at the end, so without ground truth
  // the run is not localized at the end, whatever the last updates say.
  rows[55].injected = 30;
  const DelibotSummary none = SummarizeDelibot(rows, s);
  EXPECT_EQ(none.claims_withdrawn, 2);  // the claim being built at 50-54 was never made
  EXPECT_EQ(none.standing_claim_iteration, -1);
  EXPECT_EQ(none.convergence_iteration, 0);
  EXPECT_FALSE(none.converged);
  // A dip below the consistency threshold after a claim withdraws nothing.
  std::vector<DelibotRow> dip = GoodThen(std::vector<std::pair<double, double>>(20, {0.95, 0.9}));
  dip[30].consistency = 0.1;
  const DelibotSummary dipped = SummarizeDelibot(dip, s);
  EXPECT_EQ(dipped.claims_withdrawn, 0);
  EXPECT_EQ(dipped.standing_claim_iteration, 0);
}

TEST(DelibotSummaryTest, AClaimItsAuditRefusedIsNotMadeAndANewOneNeedsTenMoreUpdates) {
  const DelibotSettings s;
  std::vector<DelibotRow> rows = GoodThen(std::vector<std::pair<double, double>>(20, {0.95, 0.9}));
  // The claim falls due at record 9 (the 10th localized update); its audit
  // refused it, so the next is due at record 19, from record 10 on.
  rows[9].claim_audit = ClaimAuditOutcome::kRefused;
  const DelibotSummary once = SummarizeDelibot(rows, s);
  EXPECT_EQ(once.claims_refused, 1);
  EXPECT_EQ(once.claims_withdrawn, 0);
  EXPECT_EQ(once.standing_claim_iteration, 10);
  // The filter's own claim is the one it made, not the refused one, and
  // without ground truth it is also the convergence.
  EXPECT_EQ(once.self_convergence_iteration, 10);
  EXPECT_EQ(once.convergence_iteration, 10);
  // A passed audit makes the claim; an audit outcome at a record where no
  // claim is due changes nothing.
  rows[19].claim_audit = ClaimAuditOutcome::kPassed;
  rows[25].claim_audit = ClaimAuditOutcome::kRefused;
  EXPECT_EQ(SummarizeDelibot(rows, s).standing_claim_iteration, 10);
  // Refused at every due record (9, 19, 29 and 39 of the 40): no claim
  // stands.
  rows[19].claim_audit = rows[29].claim_audit = rows[39].claim_audit = ClaimAuditOutcome::kRefused;
  const DelibotSummary never = SummarizeDelibot(rows, s);
  EXPECT_EQ(never.claims_refused, 4);
  EXPECT_EQ(never.standing_claim_iteration, -1);
  EXPECT_EQ(never.self_convergence_iteration, -1);
  EXPECT_EQ(never.convergence_iteration, -1);
  EXPECT_FALSE(never.converged);
}

TEST(DelibotSummaryTest, RecordsWithoutASensorUpdateAreNotEvidence) {
  const DelibotSettings s;
  // A robot standing still: 30 records, one sensor update. It has not
  // converged (10 updates needed), and the end medians come from that one.
  std::vector<DelibotRow> rows;
  for (long k = 0; k < 30; ++k) rows.push_back(Row(k, k == 0, 1.0, 0.95));
  const DelibotSummary still = SummarizeDelibot(rows, s);
  EXPECT_EQ(still.convergence_iteration, -1);
  EXPECT_DOUBLE_EQ(still.end_mode_weight, 1.0);
  // No sensor update at all: no end medians.
  for (auto& r : rows) r.sensor_updated = false;
  EXPECT_DOUBLE_EQ(SummarizeDelibot(rows, s).end_consistency, -1.0);
}

}  // namespace
}  // namespace rc
