// The sensitivity sweep (backends/calibration/sensitivity.h) on a measure
// whose answers are known: which parameters it moves, which variants flip a
// result, the CSV and flip table it writes, and the quick subset.
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "backends/calibration/sensitivity.h"
#include "calibration/fake_measure.h"
#include "support/temp_dir.h"

namespace rc {
namespace {

using test::FakeMeasure;

TEST(Sensitivity, FindsTheVariantsThatFlipAResult) {
  const Sensitivity s = SweepParameters(BackendParameters{}, FakeMeasure);
  ASSERT_EQ(s.results.size(), 2u);
  EXPECT_DOUBLE_EQ(s.baseline[0], 1.5);
  std::ostringstream flips;
  WriteFlipTable(flips, s);
  // warp buffer 2 -> 0.75x: flips; 8 -> 3x: does not.
  EXPECT_NE(flips.str().find("`robocore.warp_buffer_warps` | 2 |"), std::string::npos) << flips.str();
  EXPECT_EQ(flips.str().find("`robocore.warp_buffer_warps` | 8 |"), std::string::npos) << flips.str();
  EXPECT_NE(flips.str().find("`simt.precision` | \"fp32\""), std::string::npos) << flips.str();
  EXPECT_EQ(flips.str().find("ttaplus.warp_buffer_warps"), std::string::npos) << "TTA+'s buffer moves nothing here";
  const std::vector<ResultRange> ranges = RangesOf(s);
  EXPECT_DOUBLE_EQ(ranges[0].low, 0.75);
  EXPECT_DOUBLE_EQ(ranges[0].high, 3.0);
  EXPECT_EQ(ranges[0].low_parameter, "robocore.warp_buffer_warps=2");
}

// The CSV that WriteSensitivityCsv writes, as text.
std::string SensitivityCsvText(const Sensitivity& s) {
  const test::TempDir dir;
  WriteSensitivityCsv(dir.Path("sensitivity.csv"), s);
  std::ifstream in(dir.Path("sensitivity.csv"));
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(Sensitivity, WritesOneCsvRowPerResultAndVariant) {
  const Sensitivity s = SweepParameters(BackendParameters{}, FakeMeasure);
  const std::string csv = SensitivityCsvText(s);
  std::istringstream lines(csv);
  std::string line;
  std::getline(lines, line);
  EXPECT_EQ(line, "ratio,parameter,value,result");
  std::size_t rows = 0;
  while (std::getline(lines, line)) ++rows;
  EXPECT_EQ(rows, s.points.size());
  EXPECT_NE(csv.find("speedup,,default,1.5"), std::string::npos);
  EXPECT_NE(csv.find("speedup,robocore.warp_buffer_warps,2,0.75"), std::string::npos);
}

TEST(Sensitivity, TheQuickSubsetCoversTheParametersTheIssueNames) {
  SensitivityOptions quick;
  quick.quick = true;
  const Sensitivity s = SweepParameters(BackendParameters{}, FakeMeasure, quick);
  const Sensitivity all = SweepParameters(BackendParameters{}, FakeMeasure);
  EXPECT_LT(s.parameters_swept, all.parameters_swept);
  const std::string csv = SensitivityCsvText(s);
  for (const char* key :
       {"robocore.pre_process_initiation_cycles", "robocore.warp_buffer_warps", "robocore.sector_requests_per_cycle",
        "simt.l1_sectors_per_cycle", "robocore.op_units_per_kind_per_set", "gpu.kernel_launch_cycles",
        "robocore.program_config_cycles_per_micro_op", "simt.precision", "simt.isa", "gpu.warps_per_block"})
    EXPECT_NE(csv.find(std::string(",") + key + ","), std::string::npos) << key;
  EXPECT_EQ(csv.find(",gpu.sms,"), std::string::npos) << "the paper's SM count is not an assumption";
}

TEST(Sensitivity, AnArtifactValueIsTriedBesideTheHalfAndDouble) {
  BackendParameters artifact;
  artifact.robocore.unit.warp_buffer_warps = 5;  // neither 2 nor 8
  SensitivityOptions options;
  options.artifact = &artifact;
  const Sensitivity s = SweepParameters(BackendParameters{}, FakeMeasure, options);
  const std::string csv = SensitivityCsvText(s);
  EXPECT_NE(csv.find("speedup,robocore.warp_buffer_warps,5,1.875"), std::string::npos) << csv;
}

}  // namespace
}  // namespace rc
