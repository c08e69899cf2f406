// The sensitivity sweep's whole DeliBot runs (DelibotRunRowsUnderVariants):
// one filter run priced under many parameter sets as it runs gives, for
// every set, exactly the rows that pricing a run under that set alone
// gives (DelibotRows), including a set that moves the GPU's placement of
// warps on SMs (a run of its own) and sets that move the memory system
// (replays not shared with the baseline). And the variants do move the
// rows, so the comparison can fail.
#include <gtest/gtest.h>

#include "backends/backend_params.h"
#include "backends/calibration/delibot_calibration.h"
#include "calibration/small_calibration_options.h"

namespace rc {
namespace {

CalibrationOptions SmallRuns() {
  CalibrationOptions o = test::SmallCalibrationOptions();
  o.scenes = {};  // no SACT scene: only the DeliBot rows are compared
  return o;
}

std::vector<CalibrationRow> WholeRunRows(const std::vector<CalibrationRow>& rows) {
  std::vector<CalibrationRow> runs;
  for (const CalibrationRow& row : rows)
    if (row.result.find("whole run") != std::string::npos) runs.push_back(row);
  return runs;
}

TEST(DelibotRunSweep, EveryVariantPricesAsARunOfItsOwn) {
  const CalibrationWorkloads w = MakeCalibrationWorkloads(SmallRuns());
  ASSERT_FALSE(w.runs.empty());
  const BackendPreset base = DefaultPreset();
  const std::vector<BackendParameters> sets = {
      base.backend,
      WithParameter(base.backend, "simt.precision", "\"fp32\""),
      WithParameter(base.backend, "robocore.warp_buffer_warps", "32"),
      WithParameter(base.backend, "gpu.l1_bytes", "16384"),
      WithParameter(base.backend, "gpu.sms", "4"),
  };
  const std::vector<std::vector<CalibrationRow>> swept = DelibotRunRowsUnderVariants(w, base.kernel, sets);
  ASSERT_EQ(swept.size(), sets.size());
  int moved = 0;
  for (std::size_t v = 0; v < sets.size(); ++v) {
    const BackendPreset alone{"variant", sets[v], base.kernel};
    const std::vector<CalibrationRow> expected = WholeRunRows(DelibotRows(w, alone, alone));
    ASSERT_EQ(swept[v].size(), expected.size()) << "set " << v;
    ASSERT_EQ(expected.size(), 2 * w.runs.size());
    for (std::size_t r = 0; r < expected.size(); ++r) {
      EXPECT_EQ(swept[v][r].result, expected[r].result);
      EXPECT_EQ(swept[v][r].workload, expected[r].workload);
      EXPECT_DOUBLE_EQ(swept[v][r].ours, expected[r].ours) << expected[r].result << ", set " << v;
      EXPECT_TRUE(std::isfinite(swept[v][r].ours));
      if (v > 0 && swept[v][r].ours != swept[0][r].ours) ++moved;
    }
  }
  EXPECT_GE(moved, 4) << "the variants should move the whole-run ratios";
}

}  // namespace
}  // namespace rc
