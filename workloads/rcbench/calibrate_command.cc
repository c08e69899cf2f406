// `rcbench calibrate`: the RoboGPU paper's reported ratios beside ours,
// measured by pricing our recorded DeliBot and SACT workloads in one run
// (backends/calibration/calibration.h). Writes
//   DIR/calibration.md   the table: result | paper | ours | why ours differs
//   DIR/calibration.csv  result,unit,paper_value,ours (the plot's input)
//   DIR/calibration.png  paper vs ours bars, when python3 and matplotlib are
//                        there (scripts/plot_calibration.py); otherwise the
//                        command prints how to make it.
//
//   rcbench calibrate --out out/calibration [--params FILE.json] [--data ../shared/data]
#include <cstdlib>
#include <filesystem>
#include <iostream>

#include "backends/calibration/calibration.h"
#include "common/atomic_file.h"
#include "common/input_error.h"
#include "robocore/shipped_programs.h"
#include "workloads/rcbench/commands.h"

namespace rc {
namespace {

struct CalibrateCli {
  std::string out_dir = "calibration";
  std::string params_path;
  std::string plot_script;  // empty: <source dir>/scripts/plot_calibration.py
  CalibrationOptions options;
};

// Single-quoted for /bin/sh.
std::string ShellQuote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// The source tree's script. The binary knows the source tree only through
// the shipped programs' directory (robocore/programs, compiled in).
std::string DefaultPlotScript() {
  const std::filesystem::path source = std::filesystem::path(ShippedProgramDirectory()).parent_path().parent_path();
  return (source / "scripts" / "plot_calibration.py").string();
}

void Run(const CalibrateCli& cli) {
  const BackendParameters params =
      cli.params_path.empty() ? BackendParameters{} : LoadBackendParameters(cli.params_path);
  std::cout << "recording workloads...\n";
  const CalibrationWorkloads workloads = MakeCalibrationWorkloads(cli.options);
  std::cout << "pricing...\n";
  const CalibrationReport report = Calibrate(workloads, params);

  std::filesystem::create_directories(cli.out_dir);
  const std::string md = cli.out_dir + "/calibration.md";
  const std::string csv = cli.out_dir + "/calibration.csv";
  const std::string png = cli.out_dir + "/calibration.png";
  {
    AtomicFile file(md);
    WriteCalibrationMarkdown(file.stream(), report);
    file.Commit();
  }
  {
    AtomicFile file(csv);
    WriteCalibrationCsv(file.stream(), report);
    file.Commit();
  }
  WriteCalibrationMarkdown(std::cout, report);
  std::cout << "\nreport  " << md << "\ndata    " << csv << "\n";

  const std::string script =
      cli.plot_script.empty() ? DefaultPlotScript() : cli.plot_script;
  const std::string plot = "/usr/bin/python3 " + ShellQuote(script) + " " + ShellQuote(csv) + " " + ShellQuote(png);
  if (std::filesystem::exists(script) && std::filesystem::exists("/usr/bin/python3") &&
      std::system((plot + " >/dev/null 2>&1").c_str()) == 0)
    std::cout << "plot    " << png << "\n";
  else
    std::cout << "plot    not made here; run: " << plot << "\n";
}

}  // namespace

void AddCalibrateCommand(CLI::App& app) {
  auto cli = std::make_shared<CalibrateCli>();
  CLI::App* cmd = app.add_subcommand(
      "calibrate", "The paper's reported ratios beside ours, priced on recorded DeliBot and SACT workloads");
  cmd->add_option("--out", cli->out_dir, "Directory for calibration.md, .csv and .png")->capture_default_str();
  cmd->add_option("--params", cli->params_path, "JSON backend-parameter override file (see rcbench backends)");
  cmd->add_option("--data", cli->options.data_dir,
                  "Shared data directory (wean/wean.dat, collision/mpnet_master_obb.csv); absent files fall back to "
                  "the generated office map and random OBBs")
      ->capture_default_str();
  cmd->add_option("--particles", cli->options.particles, "DeliBot particles (count)")->capture_default_str();
  cmd->add_option("--beams", cli->options.beams, "DeliBot beams per particle (count)")->capture_default_str();
  cmd->add_option("--plot-script", cli->plot_script, "Plot script (default: the source tree's scripts/plot_calibration.py)");
  cmd->callback([cli] { Run(*cli); });
}

}  // namespace rc
