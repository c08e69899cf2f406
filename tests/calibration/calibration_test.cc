// The calibration report (backends/calibration): every row is present and
// finite in both columns, with its workload's size and a reason; every
// "ours" comes from pricing (a parameter given through the preset file moves
// the rows it should, and leaves the artifact column alone); the artifact
// preset is applied (its column differs); early exit saves on the SACT, the
// SACT latency sweep is monotone, and the datapath-variant model reproduces
// the shipped design when it has one unit of each kind.
//
// Small workloads keep the run short (a few SACT poses per scene, 12 DeliBot
// records of 40 particles); the real data is used when present, the
// generated inputs otherwise (both paths build a report).
#include <cmath>
#include <map>
#include <sstream>

#include <gtest/gtest.h>

#include "backends/backend.h"
#include "backends/calibration/calibration.h"
#include "backends/calibration/pricing_helpers.h"
#include "backends/calibration/sact_datapath_variants.h"
#include "calibration/small_calibration_options.h"
#include "common/input_error.h"
#include "support/temp_dir.h"
#include "support/test_data.h"
#include "traces/csv_table.h"

namespace rc {
namespace {

CalibrationOptions SmallOptions() { return test::SmallCalibrationOptions(); }

class CalibrationTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    workloads_ = new CalibrationWorkloads(MakeCalibrationWorkloads(SmallOptions()));
    report_ = new CalibrationReport(Calibrate(*workloads_, ArtifactPreset(), DefaultPreset()));
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
const char* const kAll = " (all scenes)";

std::vector<std::string> SactRows(const std::string& suffix) {
  std::vector<std::string> rows;
  for (const char* r : {kVsCuda, kVsCudaLaunch, kCrVsTta, kRoboVsCr, kPredication, kEnergy, kEarlyExit, kHalf, kDouble,
                        kParallel, kTwo, kSpheres})
    rows.push_back(r + suffix);
  return rows;
}

std::vector<std::string> ExpectedRows(const std::vector<std::string>& runs) {
  std::vector<std::string> rows;
  for (const std::string& run : runs)
    for (const char* vs : {"CUDA", "TTA+"})
      rows.push_back("DeliBot MCL, whole run (" + run + ", march), RoboCore vs " + vs);
  for (const char* m : {"march", "dda", "rm"})
    for (const char* vs : {"CUDA", "TTA+"}) rows.push_back(std::string("DeliBot MCL (") + m + "), RoboCore vs " + vs);
  for (const char* scene : {"cubby", "merged cubby", "dresser", "tabletop"})
    rows.push_back(std::string(kVsCuda) + " (" + scene + ")");
  for (const std::string& r : SactRows(kAll)) rows.push_back(r);
  for (const std::string& r : SactRows("")) rows.push_back(r);
  return rows;
}

std::vector<std::string> RunNames(const CalibrationWorkloads& w) {
  std::vector<std::string> names;
  for (const DelibotRunWorkload& run : w.runs) names.push_back(run.name);
  return names;
}

TEST_F(CalibrationTest, ReportHasEveryRowInBothColumnsWithItsSizeAndAReason) {
  std::vector<std::string> names;
  for (const CalibrationRow& r : report_->rows) {
    names.push_back(r.result);
    EXPECT_TRUE(std::isfinite(r.ours)) << r.result;
    EXPECT_TRUE(std::isfinite(r.artifact)) << r.result;
    EXPECT_FALSE(r.paper.empty()) << r.result;
    EXPECT_FALSE(r.workload.empty()) << r.result;
    EXPECT_GT(r.why.size(), 40u) << r.result;
    EXPECT_EQ(r.why.find("fused multiply"), std::string::npos) << r.result;
  }
  EXPECT_EQ(names, ExpectedRows(RunNames(*workloads_)));
  std::ostringstream md;
  WriteCalibrationMarkdown(md, *report_);
  for (const std::string& name : names) EXPECT_NE(md.str().find("| " + name + " |"), std::string::npos) << name;
  EXPECT_NE(md.str().find("## Paper scale"), std::string::npos);
  EXPECT_NE(md.str().find("## Small batch"), std::string::npos);
  const test::TempDir dir;
  WriteCalibrationCsv(dir.Path("calibration.csv"), *report_);
  const CsvContents csv = ReadCsv(dir.Path("calibration.csv"));
  ASSERT_EQ(csv.rows.size(), report_->rows.size());
  EXPECT_EQ(csv.header.front(), "result");
  for (std::size_t i = 0; i < names.size(); ++i) EXPECT_EQ(csv.rows[i][0], names[i]);
}

TEST_F(CalibrationTest, PaperScaleWorkloadsHaveThePapersSize) {
  ASSERT_EQ(workloads_->scenes.size(), 4u);
  for (const SactSceneWorkload& s : workloads_->scenes) {
    EXPECT_GE(s.octree_nodes, 1000u);
    EXPECT_LE(s.octree_nodes, 2000u);
    EXPECT_GE(s.sact.query_count(), 700u);
    EXPECT_NE(s.Size().find(std::to_string(s.sact.query_count()) + " queries"), std::string::npos) << s.Size();
  }
  ASSERT_FALSE(workloads_->runs.empty());
  EXPECT_EQ(workloads_->runs.front().name, "demo");
  EXPECT_NE(RowOf(*report_, "DeliBot MCL, whole run (demo, march), RoboCore vs CUDA").workload.find("updates"),
            std::string::npos);
  // The default batch floor is the paper's scale.
  EXPECT_GE(CalibrationOptions{}.min_sact_queries, 10000);
}

// The artifact preset is applied: its 8-byte cells and 7-op march, its SACT
// units and caches give other numbers than ours.
TEST_F(CalibrationTest, TheArtifactColumnIsPricedUnderTheArtifactPreset) {
  for (const std::string& row :
       {std::string("DeliBot MCL (march), RoboCore vs CUDA"), std::string(kVsCuda) + kAll, std::string(kVsCuda)})
    EXPECT_NE(RowOf(*report_, row).artifact, RowOf(*report_, row).ours) << row;
}

// Each perturbation, given through the preset file's parser, must move the
// ours column of the rows that depend on what it changes, and never the
// artifact column: the report is priced, not written down.
TEST_F(CalibrationTest, EveryOursMovesWithTheParametersItIsPricedFrom) {
  const std::map<std::string, std::vector<std::string>> moves = {
      {R"({"simt": {"isa": "sass", "fp32_latency_cycles": 12, "fp32_initiation_cycles": 6, "fp64_latency_cycles": 24,
                    "fp64_initiation_cycles": 12, "other_latency_cycles": 3, "other_initiation_cycles": 3}})",
       {"DeliBot MCL (march), RoboCore vs CUDA", "DeliBot MCL (dda), RoboCore vs CUDA",
        "DeliBot MCL (rm), RoboCore vs CUDA", kVsCuda, kVsCudaLaunch, kEnergy, kSpheres, std::string(kVsCuda) + kAll}},
      {R"({"robocore": {"cmp_cycles": 4, "return_cycles": 3, "box_normal_cycles": 20, "edge_edge_cycles": 18,
                        "pre_process_cycles": 30}})",
       {"DeliBot MCL (march), RoboCore vs TTA+", "DeliBot MCL (dda), RoboCore vs TTA+",
        "DeliBot MCL (rm), RoboCore vs TTA+", kRoboVsCr, kEarlyExit, kHalf, kDouble, kParallel, kTwo, kSpheres,
        std::string(kRoboVsCr) + kAll}},
      {R"({"ttaplus": {"predicated_op_cycles": 4, "addsub_cycles": 6}})", {kCrVsTta, kPredication}},
      {R"({"robocore": {"sact_latency_scale": 2.0}})", {kHalf, kDouble}},
      {R"({"kernel": {"grid_cell_bytes": 8}})", {"DeliBot MCL (march), RoboCore vs CUDA"}},
  };
  for (const auto& [json, rows] : moves) {
    const CalibrationReport changed =
        Calibrate(*workloads_, ArtifactPreset(), ParseBackendPreset(json, "perturbation.json"));
    for (const std::string& row : rows) {
      EXPECT_NE(Ours(changed, row), Ours(*report_, row)) << row << " did not move under " << json;
      EXPECT_EQ(RowOf(changed, row).artifact, RowOf(*report_, row).artifact) << row;
    }
  }
}

TEST_F(CalibrationTest, EarlyExitSavesComputationOnTheSact) {
  for (const std::string& row : {std::string(kEarlyExit), std::string(kEarlyExit) + kAll}) {
    EXPECT_LT(Ours(*report_, row), 0.0) << row;  // a negative change: a saving
    EXPECT_GT(Ours(*report_, row), -100.0) << row;
  }
}

TEST_F(CalibrationTest, SactLatencySweepIsMonotone) {
  for (const std::string suffix : {"", kAll}) {
    EXPECT_LE(Ours(*report_, kHalf + suffix), 0.0);
    EXPECT_GE(Ours(*report_, kDouble + suffix), 0.0);
    EXPECT_LT(Ours(*report_, kHalf + suffix), Ours(*report_, kDouble + suffix));
  }
}

TEST_F(CalibrationTest, MoreSactUnitsNeverSlowAQueryDown) {
  for (const std::string suffix : {"", kAll}) {
    EXPECT_LE(Ours(*report_, kParallel + suffix), 0.0);
    EXPECT_GE(Ours(*report_, kTwo + suffix), 1.0);
  }
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
  const std::uint32_t round =
      static_cast<std::uint32_t>(datapath.latencies.pre_process_cycles + datapath.latencies.edge_edge_cycles);
  EXPECT_EQ(timing.loop.Cost(0).cycles, round);
  EXPECT_GT(timing.loop.Cost(kNoExit).cycles, round);  // + PUSH
  for (std::uint8_t exit : parallel.node_exits) EXPECT_TRUE(exit == 0 || exit == kNoExit);
}

// Without the shared data: the generated office map and random OBBs, said
// so in the report, the demo run only, and still every row.
TEST(CalibrationFallback, GeneratedInputsGiveEveryRowAndSaySo) {
  CalibrationOptions o = SmallOptions();
  o.data_dir = "/nonexistent-calibration-data";
  o.random_obbs = 64;
  o.min_sact_queries = 128;
  const CalibrationWorkloads w = MakeCalibrationWorkloads(o);
  std::string notes;
  for (const std::string& n : w.notes) notes += n + "\n";
  EXPECT_NE(notes.find("generated office map"), std::string::npos) << notes;
  EXPECT_NE(notes.find("random"), std::string::npos) << notes;
  EXPECT_NE(notes.find("robotdata1: not run"), std::string::npos) << notes;
  EXPECT_EQ(w.sact.query_count(), 64u);
  const CalibrationReport report = Calibrate(w, ArtifactPreset(), DefaultPreset());
  std::vector<std::string> names;
  for (const CalibrationRow& r : report.rows) {
    names.push_back(r.result);
    EXPECT_TRUE(std::isfinite(r.ours)) << r.result;
  }
  EXPECT_EQ(names, ExpectedRows({"demo"}));
}

TEST(SactDatapathVariants, RoundsMustCoverEveryAxisOnce) {
  SactDatapathVariant bad = SactUnitCopies(2);
  bad.rounds.pop_back();
  EXPECT_THROW(VariantProgram(bad, OpUnitLatencies{}), std::invalid_argument);
  EXPECT_EQ(SactUnitCopies(2).rounds.size(), 3u + 5u);
  EXPECT_EQ(SactUnitCopies(6).rounds.size(), 1u + 2u);
}

TEST(CalibrationOptions, RejectsImpossibleSizes) {
  CalibrationOptions o;
  o.min_sact_queries = 0;
  EXPECT_THROW(MakeCalibrationWorkloads(o), UsageError);
  o = CalibrationOptions{};
  o.run_beam_step = 0;
  std::string error;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("beam step"), std::string::npos);
}

}  // namespace
}  // namespace rc
