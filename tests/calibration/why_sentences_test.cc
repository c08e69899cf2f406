// The "why ours differs" column is computed: each clause is chosen by the
// bound the run measured. Unit level: every bound text a backend writes
// maps to its kind and its clause; an unknown one is an error. Report
// level: a parameter change that moves RoboCore's (and the CUDA cores')
// limiting bound changes the printed sentence to the new bound's clause.
#include <set>

#include <gtest/gtest.h>

#include "backends/calibration/calibration.h"
#include "backends/calibration/why_sentences.h"
#include "support/test_data.h"

namespace rc {
namespace {

BatchCost Cost(const std::string& bound, bool simt) {
  BatchCost c;
  c.bound = bound;
  c.cycles = 10000;
  c.launch_cycles = 5000;
  c.clock_hz = 1e9;
  c.queries = 64;
  c.warp_instructions = 1000;
  c.thread_instructions = 16000;
  c.simt_efficiency = simt ? 0.5 : std::numeric_limits<double>::quiet_NaN();
  c.memory.sector_requests = 100;
  c.memory.l1_hits = 75;
  return c;
}

TEST(WhySentences, EveryBoundTheBackendsWriteHasItsClause) {
  struct Case {
    const char* bound;
    bool simt;
    BoundKind kind;
    const char* clause;
  };
  const Case cases[] = {
      {"latency (resident warps)", true, BoundKind::kLatency, "latency-bound"},
      {"issue", true, BoundKind::kIssue, "issue-bound"},
      {"SFU pipe", true, BoundKind::kPipe, "SFU pipe"},
      {"FP64 pipe", true, BoundKind::kPipe, "FP64 pipe"},
      {"L1 bandwidth", true, BoundKind::kL1, "L1 bandwidth"},
      {"DRAM bandwidth", true, BoundKind::kDram, "DRAM bandwidth"},
      {"latency (warp buffer)", false, BoundKind::kLatency, "warp buffer"},
      {"op unit BOX_NORMAL", false, BoundKind::kOpUnit, "Box-Normal"},
      {"op unit CMP", false, BoundKind::kOpUnit, "CMP OP unit"},
      {"L1 requests", false, BoundKind::kL1, "L1 bandwidth"},
      {"thread intake", false, BoundKind::kThreadIntake, "thread intake"},
  };
  std::set<std::string> sentences;
  for (const Case& c : cases) {
    EXPECT_EQ(ClassifyBound(c.bound), c.kind) << c.bound;
    SideEvidence side(c.simt ? "the CUDA cores" : "RoboCore");
    side.Add(Cost(c.bound, c.simt));
    const std::string clause = BoundClause(side);
    EXPECT_NE(clause.find(c.clause), std::string::npos) << c.bound << ": " << clause;
    sentences.insert(clause);
  }
  EXPECT_EQ(sentences.size(), std::size(cases));  // no two bounds read alike
  EXPECT_THROW(ClassifyBound("luck"), std::logic_error);
}

// Over several launches the bound of the most kernel cycles speaks, with
// its share; the launch is named only when it is a large share.
TEST(WhySentences, SeveralLaunchesReportTheDominantBoundAndItsShare) {
  SideEvidence side("RoboCore");
  BatchCost a = Cost("L1 requests", false), b = Cost("latency (warp buffer)", false);
  b.cycles = 5000 + 15000;  // three times a's kernel cycles
  side.Add(a);
  side.Add(b);
  EXPECT_EQ(side.bound(), "latency (warp buffer)");
  EXPECT_DOUBLE_EQ(side.bound_share(), 0.75);
  EXPECT_NE(BoundClause(side).find("75% of its kernel cycles"), std::string::npos) << BoundClause(side);
  SideEvidence simt("the CUDA cores");
  simt.Add(Cost("issue", true));
  EXPECT_NE(CompareSides(side, simt).find("the launch is"), std::string::npos);  // 5000 of 30000 and of 10000
  BatchCost big = Cost("issue", true);
  big.cycles = 5000 + 1000000;
  SideEvidence busy("the CUDA cores");
  busy.Add(big);
  EXPECT_EQ(CompareSides(busy, busy).find("the launch is"), std::string::npos);
}

const CalibrationRow& Row(const CalibrationReport& report, const std::string& result) {
  for (const CalibrationRow& r : report.rows)
    if (r.result == result) return r;
  ADD_FAILURE() << "no row " << result;
  static const CalibrationRow none;
  return none;
}

// RoboCore on the SACT is latency-bound with our defaults; with a deep warp
// buffer and unpipelined SACT units its busiest unit is a SACT unit, and
// with one scheduler per SM the CUDA cores become issue- or pipe-bound.
// The printed sentence follows each change.
TEST(WhySentences, TheSentenceFollowsTheMeasuredBound) {
  CalibrationOptions o;
  o.data_dir = RC_SHARED_DATA_DIR;
  o.particles = 8;
  o.beams = 30;
  o.min_sact_queries = 2000;
  o.scenes = {MpinetSceneKind::kCubby};
  o.delibot_runs = false;
  const CalibrationWorkloads w = MakeCalibrationWorkloads(o);
  const std::string row = "SACT collision queries, RoboCore vs CUDA (all scenes)";
  const BackendPreset artifact = ArtifactPreset();

  const CalibrationReport base = Calibrate(w, artifact, DefaultPreset());
  const std::string& base_why = Row(base, row).why;
  ASSERT_NE(base_why.find("RoboCore is latency-bound"), std::string::npos) << base_why;

  const BackendPreset throughput = ParseBackendPreset(
      R"({"robocore": {"warp_buffer_warps": 64, "pre_process_initiation_cycles": 14,
                 "box_normal_initiation_cycles": 12, "edge_edge_initiation_cycles": 12}})",
      "throughput.json");
  // Each report is kept: a row of a temporary report dies with it.
  const CalibrationReport unit = Calibrate(w, artifact, throughput);
  const std::string& unit_why = Row(unit, row).why;
  EXPECT_EQ(unit_why.find("RoboCore is latency-bound"), std::string::npos) << unit_why;
  EXPECT_NE(unit_why.find("OP unit"), std::string::npos) << unit_why;
  EXPECT_NE(unit_why.find("SACT"), std::string::npos) << unit_why;

  const BackendPreset one_scheduler =
      ParseBackendPreset(R"({"simt": {"schedulers_per_sm": 1}, "gpu": {"max_warps_per_sm": 64,
                            "registers_per_sm": 131072}})",
                         "one.json");
  const CalibrationReport simt = Calibrate(w, artifact, one_scheduler);
  const std::string& simt_why = Row(simt, row).why;
  EXPECT_EQ(simt_why.find("the CUDA cores are latency-bound"), std::string::npos) << simt_why;
  EXPECT_TRUE(simt_why.find("issue-bound") != std::string::npos || simt_why.find("pipe") != std::string::npos)
      << simt_why;
  EXPECT_NE(base_why, unit_why);
  EXPECT_NE(base_why, simt_why);
}

}  // namespace
}  // namespace rc
