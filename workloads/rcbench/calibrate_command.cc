// `rcbench calibrate`: the RoboGPU paper's reported ratios beside ours,
// measured by pricing our recorded DeliBot and SACT workloads in one run,
// under the artifact preset and under ours (backends/calibration/
// calibration.h). Writes
//   DIR/calibration.md   the tables: result | workload | paper | artifact preset | ours | why ours differs
//   DIR/calibration.csv  result,scale,unit,workload,paper_value,artifact,ours,... (the plot's input)
//   DIR/calibration.png  paper vs ours bars, when python3 and matplotlib are
//                        there (scripts/plot_calibration.py); otherwise the
//                        command prints how to make it.
//
// With --sensitivity, also every declared parameter swept one at a time
// (backends/calibration/sensitivity.h):
//   DIR/sensitivity.csv  ratio,parameter,value,result
//   DIR/flips.md         the parameters whose range flips a result
//   DIR/sensitivity.png  a tornado plot per result (scripts/plot_sensitivity.py)
//   DIR/sensitivity_artifact.csv, flips_artifact.md, sensitivity_artifact.png
//                        the same around the artifact preset's values
// Every path is checked before the work starts, and every file written once
// it is done, the data files before the figures, whose scripts read them
// (backends/calibration/calibration_outputs.h).
//
//   rcbench calibrate --out out/calibration [--backend-params artifact|FILE.json] [--data ../shared/data]
//                     [--sensitivity [--quick]]
#include <filesystem>
#include <iostream>

#include "backends/calibration/calibration.h"
#include "backends/calibration/calibration_outputs.h"
#include "backends/calibration/delibot_calibration.h"
#include "backends/calibration/sensitivity.h"
#include "common/atomic_file.h"
#include "common/exit_codes.h"
#include "common/input_error.h"
#include "robocore/shipped_programs.h"
#include "workloads/rcbench/commands.h"

namespace rc {
namespace {

struct CalibrateCli {
  std::string out_dir = "calibration";
  std::string params_path;
  std::string plot_script;  // empty: <source dir>/scripts/plot_calibration.py
  bool sensitivity = false, quick = false;
  CalibrationOptions options;
};

// A script of the source tree. The binary knows the source tree only
// through the shipped programs' directory (robocore/programs, compiled in).
std::string SourceScript(const std::string& name) {
  const std::filesystem::path source = std::filesystem::path(ShippedProgramDirectory()).parent_path().parent_path();
  return (source / "scripts" / name).string();
}

// Sweeps one column's parameters, the other preset's values included as
// variants, and sets each row's range for that column to the lowest and
// highest value the sweep found. Every row is swept: the small batches and
// SACT scenes re-priced per variant, the whole DeliBot runs filtered once
// and priced under every variant as they run (DelibotRunRowsUnderVariants).
// Writes nothing: the files come once both columns are swept
// (WriteCalibrationOutputs).
SweptColumn SweepColumn(const CalibrateCli& cli, const CalibrationWorkloads& workloads, const BackendPreset& swept,
                        const BackendPreset& other, const std::string& suffix, bool ours_column,
                        CalibrationReport& report) {
  SensitivityOptions options;
  options.quick = cli.quick;
  options.artifact = &other.backend;
  std::cout << "sweeping " << (cli.quick ? "the quick subset of the" : "every") << " declared parameter"
            << (cli.quick ? "s" : "") << " of the " << (ours_column ? "ours" : "artifact preset") << " column...\n";
  const MeasureAllRows measure = [&](const std::vector<BackendParameters>& sets) {
    std::vector<std::vector<CalibrationRow>> rows = DelibotRunRowsUnderVariants(workloads, swept.kernel, sets);
    for (std::size_t v = 0; v < sets.size(); ++v)
      for (CalibrationRow& row :
           CalibrateOneColumn(workloads, BackendPreset{swept.name, sets[v], swept.kernel}, false).rows)
        rows[v].push_back(std::move(row));
    return rows;
  };
  SweptColumn column{suffix, SweepParametersTogether(swept.backend, measure, options)};
  const Sensitivity& s = column.sweep;
  std::cout << s.parameters_swept << " parameters swept, " << s.points.size() - s.results.size() << " variants priced, "
            << s.skipped.size() << " refused by the parameter checks\n";
  WriteFlipTable(std::cout, s);
  const std::vector<ResultRange> ranges = RangesOf(s);
  for (std::size_t i = 0; i < ranges.size(); ++i)
    for (CalibrationRow& row : report.rows)
      if (row.result == s.results[i].name)
        (ours_column ? row.ours_range : row.artifact_range) = ValueRange{ranges[i].low, ranges[i].high};
  return column;
}

void Run(const CalibrateCli& cli) {
  const std::vector<std::string> suffixes =
      cli.sensitivity ? std::vector<std::string>{"", "_artifact"} : std::vector<std::string>{};
  CheckOutputPaths(CalibrationOutputPaths(cli.out_dir, suffixes));
  const BackendPreset ours = cli.params_path.empty() ? DefaultPreset() : LoadBackendPreset(cli.params_path);
  const BackendPreset artifact = ArtifactPreset();
  std::cout << "recording workloads...\n";
  const CalibrationWorkloads workloads = MakeCalibrationWorkloads(cli.options);
  std::cout << "pricing (artifact preset and " << ours.name << ")...\n";
  CalibrationReport report = Calibrate(workloads, artifact, ours);

  std::vector<SweptColumn> sweeps;
  if (cli.sensitivity) {
    sweeps.push_back(SweepColumn(cli, workloads, ours, artifact, suffixes[0], true, report));
    sweeps.push_back(SweepColumn(cli, workloads, artifact, ours, suffixes[1], false, report));
  }
  WriteCalibrationMarkdown(std::cout, report);
  std::cout << "\n";
  const PlotScripts scripts{cli.plot_script.empty() ? SourceScript("plot_calibration.py") : cli.plot_script,
                            SourceScript("plot_sensitivity.py")};
  WriteCalibrationOutputs(cli.out_dir, report, sweeps, scripts, DrawWithPython, std::cout);
}

}  // namespace

void AddCalibrateCommand(CLI::App& app) {
  auto cli = std::make_shared<CalibrateCli>();
  CLI::App* cmd = app.add_subcommand(
      "calibrate", "The paper's reported ratios beside ours, priced on recorded DeliBot and SACT workloads");
  cmd->add_option("--out", cli->out_dir, "Directory for calibration.md, .csv and .png")->capture_default_str();
  cmd->add_option("--backend-params", cli->params_path,
                  "The ours column's parameters: a named preset (artifact) or a JSON file overriding backend cost "
                  "parameters (see rcbench backends; may hold a \"kernel\" object, as backends/presets/artifact.json)");
  cmd->add_flag("--sensitivity", cli->sensitivity,
                "Also sweep every declared parameter over x0.5 and x2 (choices: every value), one at a time: "
                "sensitivity.csv, flips.md, sensitivity.png; and around the artifact preset: *_artifact.*");
  cmd->add_flag("--quick", cli->quick,
                "With --sensitivity: only the parameters whose source is an assumption and those issue #20 names")
      ->needs("--sensitivity");
  cmd->add_option("--data", cli->options.data_dir,
                  "Shared data directory (wean/wean.dat, collision/mpnet_master_obb.csv); absent files fall back to "
                  "the generated office map and random OBBs")
      ->capture_default_str();
  cmd->add_option("--particles", cli->options.particles, "Small-batch DeliBot particles (count)")
      ->capture_default_str();
  cmd->add_option("--beams", cli->options.beams, "DeliBot beams per particle (count)")->capture_default_str();
  cmd->add_option("--sact-queries", cli->options.min_sact_queries,
                  "Paper-scale SACT queries per scene, at least (count)")
      ->capture_default_str();
  cmd->add_option("--delibot-runs", cli->options.delibot_runs, "Price whole DeliBot runs (demo, robotdata1)")
      ->capture_default_str();
  cmd->add_option("--run-max-records", cli->options.run_max_records,
                  "DeliBot runs: at most N laser records (count; 0 = the whole trace)")
      ->capture_default_str();
  cmd->add_option("--plot-script", cli->plot_script,
                  "Plot script (default: the source tree's scripts/plot_calibration.py)");
  cmd->footer(ExitCodeFooter(""));
  cmd->callback([cli] { Run(*cli); });
}

}  // namespace rc
