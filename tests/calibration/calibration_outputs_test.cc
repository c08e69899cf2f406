// The files of `rcbench calibrate --out DIR` (backends/calibration/
// calibration_outputs.h): every data file is in place before any figure is
// drawn, so that scripts/plot_sensitivity.py, which reads calibration.csv
// beside the sweep, draws the tornados into a fresh folder (it did not
// while the command wrote calibration.csv after drawing them); and a
// figure not drawn says why and how to make it. The sweep is a stand-in
// measure, so these run in seconds where the real --quick sweep takes
// minutes.
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "backends/calibration/calibration_outputs.h"
#include "calibration/fake_measure.h"
#include "support/temp_dir.h"

namespace rc {
namespace {

using test::FakeMeasure;

CalibrationReport FakeReport() {
  CalibrationReport report;
  report.ours_name = "default";
  report.rows = FakeMeasure(BackendParameters{});
  for (CalibrationRow& row : report.rows) {
    row.workload = "a stand-in";
    row.paper = "1.2x faster";
    row.paper_value = 1.2;
    row.artifact = row.ours;
  }
  return report;
}

std::vector<SweptColumn> FakeSweeps() {
  const Sensitivity sweep = SweepParameters(BackendParameters{}, FakeMeasure);
  return {{"", sweep}, {"_artifact", sweep}};
}

PlotScripts SourceTreeScripts() {
  return {std::string(RC_SOURCE_DIR) + "/scripts/plot_calibration.py",
          std::string(RC_SOURCE_DIR) + "/scripts/plot_sensitivity.py"};
}

TEST(CalibrationOutputs, EveryDataFileIsInPlaceBeforeAnyFigureIsDrawn) {
  const test::TempDir dir;
  const std::string out = dir.Path("fresh");  // not there yet, as a new --out folder
  std::vector<std::string> drawn;
  const DrawFigure check = [&](const Figure& figure) {
    for (const std::string& path : CalibrationOutputPaths(out, {"", "_artifact"})) {
      if (std::filesystem::path(path).extension() == ".png") continue;
      EXPECT_TRUE(std::filesystem::exists(path)) << path << " is not written when " << figure.png << " is drawn";
    }
    EXPECT_TRUE(std::filesystem::exists(figure.input)) << figure.input;
    drawn.push_back(std::filesystem::path(figure.png).filename().string());
    return std::string("a stand-in draws nothing");
  };
  std::ostringstream log;
  WriteCalibrationOutputs(out, FakeReport(), FakeSweeps(), SourceTreeScripts(), check, log);
  EXPECT_EQ(drawn, (std::vector<std::string>{"sensitivity.png", "sensitivity_artifact.png", "calibration.png"}));
  EXPECT_NE(log.str().find("data    " + out + "/calibration.csv\n"), std::string::npos) << log.str();
  EXPECT_NE(log.str().find("plot    not made here (a stand-in draws nothing); run: /usr/bin/python3 '" +
                           SourceTreeScripts().sensitivity + "' '" + out + "/sensitivity.csv' '" + out +
                           "/sensitivity.png'\n"),
            std::string::npos)
      << log.str();
}

TEST(CalibrationOutputs, ThePlotScriptsDrawEveryFigureIntoAFreshFolder) {
  // The scripts need matplotlib, which scripts/setup installs for Debian's
  // interpreter (python3-matplotlib); DrawWithPython runs that one.
  if (std::system("/usr/bin/python3 -c 'import matplotlib' >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "/usr/bin/python3 cannot import matplotlib (install python3-matplotlib, scripts/setup): "
                    "the figures were not drawn, only their order was checked";
  const test::TempDir dir;
  const std::string out = dir.Path("fresh");
  std::ostringstream log;
  WriteCalibrationOutputs(out, FakeReport(), FakeSweeps(), SourceTreeScripts(), DrawWithPython, log);
  EXPECT_EQ(log.str().find("not made here"), std::string::npos) << log.str();
  for (const char* png : {"sensitivity.png", "sensitivity_artifact.png", "calibration.png"}) {
    const std::string path = out + "/" + png;
    EXPECT_TRUE(std::filesystem::exists(path) && std::filesystem::file_size(path) > 1000) << path << "\n" << log.str();
  }
  // Nothing but the outputs: no temporary file of an atomic write is left.
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(out)) ++files;
  EXPECT_EQ(files, CalibrationOutputPaths(out, {"", "_artifact"}).size());
}

TEST(CalibrationOutputs, AFigureNotDrawnSaysWhy) {
  const test::TempDir dir;
  EXPECT_EQ(DrawWithPython({dir.Path("no_such_script.py"), "in.csv", dir.Path("out.png")}),
            "no " + dir.Path("no_such_script.py"));
  if (!std::filesystem::exists("/usr/bin/python3")) GTEST_SKIP() << "no /usr/bin/python3: a failing script not run";
  const std::string failing =
      dir.Write("failing.py", "import sys\nprint('drawn?')\nsys.exit('no figure: bad input')\n");
  EXPECT_EQ(DrawWithPython({failing, "in.csv", dir.Path("out.png")}), "the script failed: no figure: bad input");
  EXPECT_FALSE(std::filesystem::exists(dir.Path("out.png")));
}

}  // namespace
}  // namespace rc
