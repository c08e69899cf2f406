// The calibration report (backends/calibration): every row is present and
// finite, every "ours" comes from pricing (a parameter given through the
// JSON override moves the row it should), early exit saves on the SACT, the
// SACT latency sweep is monotone, and the datapath-variant model reproduces
// the shipped design when it has one unit of each kind.
//
// A small DeliBot batch keeps the run short; the real data is used when
// present, the generated inputs otherwise (both paths build a report).
#include <cmath>
#include <map>
#include <sstream>

#include <gtest/gtest.h>

#include "backends/backend.h"
#include "backends/calibration/calibration.h"
#include "backends/calibration/pricing_helpers.h"
#include "backends/calibration/sact_datapath_variants.h"
#include "test_data.h"

namespace rc {
namespace {

CalibrationOptions SmallOptions() {
  CalibrationOptions o;
  o.data_dir = RC_SHARED_DATA_DIR;
  o.particles = 24;
  o.beams = 60;
  o.random_obbs = 200;
  return o;
}

class CalibrationTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    workloads_ = new CalibrationWorkloads(MakeCalibrationWorkloads(SmallOptions()));
    report_ = new CalibrationReport(Calibrate(*workloads_, BackendParameters{}));
  }
  static void TearDownTestSuite() {
    delete report_;
    delete workloads_;
  }
  static const CalibrationRow& RowOf(const CalibrationReport& report, const std::string& result) {
    for (const CalibrationRow& r : report.rows)
      if (r.result == result) return r;
    ADD_FAILURE() << "no row '" << result << "'";
    static const CalibrationRow none;
    return none;
  }
  static double Ours(const CalibrationReport& report, const std::string& result) { return RowOf(report, result).ours; }

  static CalibrationWorkloads* workloads_;
  static CalibrationReport* report_;
};
CalibrationWorkloads* CalibrationTest::workloads_ = nullptr;
CalibrationReport* CalibrationTest::report_ = nullptr;

const char* const kVsCuda = "SACT collision queries, RoboCore vs CUDA";
const char* const kVsCudaLaunch = "SACT collision queries, RoboCore vs CUDA, incl. launch";
const char* const kCrVsTta = "SACT, TTA+ with conditional return vs TTA+";
const char* const kRoboVsCr = "SACT, RoboCore vs TTA+ with conditional return";
const char* const kPredication = "SACT, TTA+ with predication vs TTA+";
const char* const kEnergy = "SACT collision queries, energy RoboCore vs CUDA";
const char* const kEarlyExit = "SACT early exit, average computation latency per query (RoboCore)";
const char* const kHalf = "SACT unit latency x0.5, RoboCore total time";
const char* const kDouble = "SACT unit latency x2, RoboCore total time";
const char* const kParallel = "Fully parallel SACT (6 box + 9 edge units), RoboCore total time";
const char* const kTwo = "Two of each SACT unit, RoboCore";
const char* const kSpheres = "Sphere robot on RoboCore vs OBB SACT on CUDA";

std::vector<std::string> ExpectedRows() {
  std::vector<std::string> rows;
  for (const char* m : {"march", "dda", "rm"}) {
    rows.push_back(std::string("DeliBot MCL (") + m + "), RoboCore vs CUDA");
    rows.push_back(std::string("DeliBot MCL (") + m + "), RoboCore vs TTA+");
  }
  for (const char* r : {kVsCuda, kVsCudaLaunch, kCrVsTta, kRoboVsCr, kPredication, kEnergy, kEarlyExit, kHalf,
                        kDouble, kParallel, kTwo, kSpheres})
    rows.push_back(r);
  return rows;
}

TEST_F(CalibrationTest, ReportHasEveryRowFiniteWithAReason) {
  std::vector<std::string> names;
  for (const CalibrationRow& r : report_->rows) {
    names.push_back(r.result);
    EXPECT_TRUE(std::isfinite(r.ours)) << r.result;
    EXPECT_FALSE(r.paper.empty()) << r.result;
    EXPECT_GT(r.why.size(), 40u) << r.result;
  }
  EXPECT_EQ(names, ExpectedRows());
  EXPECT_EQ(report_->workload_notes.size(), 2u);
  std::ostringstream md, csv;
  WriteCalibrationMarkdown(md, *report_);
  WriteCalibrationCsv(csv, *report_);
  for (const std::string& name : ExpectedRows()) EXPECT_NE(md.str().find("| " + name + " |"), std::string::npos) << name;
  std::size_t lines = 0;
  for (char c : csv.str()) lines += c == '\n';
  EXPECT_EQ(lines, report_->rows.size() + 1);
}

// Each perturbation, given through the JSON override file's parser, must
// move the rows that depend on what it changes: the report is priced, not
// written down.
TEST_F(CalibrationTest, EveryOursMovesWithTheParametersItIsPricedFrom) {
  const std::map<std::string, std::vector<std::string>> moves = {
      {R"({"simt": {"isa": "sass", "fp32_latency_cycles": 12, "fp32_initiation_cycles": 6, "fp64_latency_cycles": 24,
                    "fp64_initiation_cycles": 12, "other_latency_cycles": 3, "other_initiation_cycles": 3}})",
       {"DeliBot MCL (march), RoboCore vs CUDA", "DeliBot MCL (dda), RoboCore vs CUDA",
        "DeliBot MCL (rm), RoboCore vs CUDA", kVsCuda, kVsCudaLaunch, kEnergy, kSpheres}},
      {R"({"robocore": {"cmp_cycles": 4, "return_cycles": 3, "box_normal_cycles": 20, "edge_edge_cycles": 18,
                        "pre_process_cycles": 30}})",
       {"DeliBot MCL (march), RoboCore vs TTA+", "DeliBot MCL (dda), RoboCore vs TTA+",
        "DeliBot MCL (rm), RoboCore vs TTA+", kRoboVsCr, kEarlyExit, kHalf, kDouble, kParallel, kTwo, kSpheres}},
      {R"({"ttaplus": {"predicated_op_cycles": 4, "addsub_cycles": 6}})", {kCrVsTta, kPredication}},
      {R"({"robocore": {"sact_latency_scale": 2.0}})", {kHalf, kDouble}},
  };
  for (const auto& [json, rows] : moves) {
    const CalibrationReport changed = Calibrate(*workloads_, ParseBackendParameters(json, "perturbation.json"));
    for (const std::string& row : rows)
      EXPECT_NE(Ours(changed, row), Ours(*report_, row)) << row << " did not move under " << json;
  }
}

TEST_F(CalibrationTest, EarlyExitSavesComputationOnTheSact) {
  EXPECT_LT(Ours(*report_, kEarlyExit), 0.0);  // a negative change: a saving
  EXPECT_GT(Ours(*report_, kEarlyExit), -100.0);
}

TEST_F(CalibrationTest, SactLatencySweepIsMonotone) {
  EXPECT_LE(Ours(*report_, kHalf), 0.0);
  EXPECT_GE(Ours(*report_, kDouble), 0.0);
  EXPECT_LT(Ours(*report_, kHalf), Ours(*report_, kDouble));
}

TEST_F(CalibrationTest, MoreSactUnitsNeverSlowAQueryDown) {
  EXPECT_LE(Ours(*report_, kParallel), 0.0);
  EXPECT_GE(Ours(*report_, kTwo), 1.0);
}

// One unit of each kind, one axis per round, is the shipped design: the
// variant model must price it exactly as the shipped program.
TEST_F(CalibrationTest, OneUnitOfEachKindIsTheShippedDesign) {
  const BackendParameters params;
  const OpUnitLatencies latencies = params.robocore.Datapath().latencies;
  const KernelRecord same = VariantRecord(workloads_->sact, SactUnitCopies(1), latencies);
  EXPECT_EQ(same.node_exits, workloads_->sact.node_exits);
  const auto robocore = Backend::Create("robocore", params);
  const BatchCost shipped = robocore->Price(workloads_->sact);
  const BatchCost variant = robocore->Price(same);
  EXPECT_EQ(variant.cycles - variant.launch_cycles, shipped.cycles - shipped.launch_cycles);
  EXPECT_DOUBLE_EQ(AverageComputationCycles(same, params.robocore.Datapath()),
                   AverageComputationCycles(workloads_->sact, params.robocore.Datapath()));
}

// Fully parallel: a node costs PRE + one unit, whichever axis separates.
TEST_F(CalibrationTest, FullyParallelNodeCostsOneRound) {
  const BackendParameters params;
  const DatapathConfig datapath = params.robocore.Datapath();
  const KernelRecord parallel = VariantRecord(workloads_->sact, FullyParallelSact(), datapath.latencies);
  const ProgramTiming timing(*parallel.program, nullptr, datapath);
  ASSERT_EQ(timing.loop.return_count(), 1);
  const std::uint32_t round = static_cast<std::uint32_t>(datapath.latencies.pre_process_cycles +
                                                         datapath.latencies.edge_edge_cycles);
  EXPECT_EQ(timing.loop.Cost(0).cycles, round);
  EXPECT_GT(timing.loop.Cost(kNoExit).cycles, round);  // + PUSH
  for (std::uint8_t exit : parallel.node_exits) EXPECT_TRUE(exit == 0 || exit == kNoExit);
}

// Without the shared data: the generated office map and random OBBs, said
// so in the report, and still every row.
TEST(CalibrationFallback, GeneratedInputsGiveEveryRowAndSaySo) {
  CalibrationOptions o = SmallOptions();
  o.data_dir = "/nonexistent-calibration-data";
  o.random_obbs = 64;
  const CalibrationWorkloads w = MakeCalibrationWorkloads(o);
  EXPECT_NE(w.ray_description.find("generated office map"), std::string::npos) << w.ray_description;
  EXPECT_NE(w.collision_description.find("random"), std::string::npos) << w.collision_description;
  EXPECT_EQ(w.sact.query_count(), 64u);
  const CalibrationReport report = Calibrate(w, BackendParameters{});
  std::vector<std::string> names;
  for (const CalibrationRow& r : report.rows) {
    names.push_back(r.result);
    EXPECT_TRUE(std::isfinite(r.ours)) << r.result;
  }
  EXPECT_EQ(names, ExpectedRows());
}

TEST(SactDatapathVariants, RoundsMustCoverEveryAxisOnce) {
  SactDatapathVariant bad = SactUnitCopies(2);
  bad.rounds.pop_back();
  EXPECT_THROW(VariantProgram(bad, OpUnitLatencies{}), std::invalid_argument);
  EXPECT_EQ(SactUnitCopies(2).rounds.size(), 3u + 5u);
  EXPECT_EQ(SactUnitCopies(6).rounds.size(), 1u + 2u);
}

}  // namespace
}  // namespace rc
