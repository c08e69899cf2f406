#pragma once
// What `rcbench calibrate --out DIR` writes, and in which order: every data
// file first, each atomic (common/atomic_file.h), and only then the figures,
// because a plot script may read more than the file it is handed:
// scripts/plot_sensitivity.py takes each result's unit from the
// calibration.csv beside the sweep (it draws the speedups only). Drawn while
// calibration.csv was not yet written, a fresh --out folder got no tornado.
//
//   DIR/calibration.md, calibration.csv   the report (calibration_row.h)
//   DIR/sensitivity<S>.csv, flips<S>.md   per swept column (sensitivity.h);
//                                         S is "" for ours, "_artifact"
//   DIR/sensitivity<S>.png                the tornado (scripts/plot_sensitivity.py)
//   DIR/calibration.png                   paper vs ours (scripts/plot_calibration.py)
#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

#include "backends/calibration/calibration_row.h"
#include "backends/calibration/sensitivity.h"

namespace rc {

// One column's sweep and the suffix of its files.
struct SweptColumn {
  std::string suffix;  // "" (ours) or "_artifact"
  Sensitivity sweep;
};

// A figure a plot script draws: `python3 SCRIPT INPUT PNG`.
struct Figure {
  std::string script, input, png;
};
// Draws a figure; returns "" when it did, otherwise why not (for the user).
using DrawFigure = std::function<std::string(const Figure&)>;

struct PlotScripts {
  std::string calibration;  // scripts/plot_calibration.py, or --plot-script
  std::string sensitivity;  // scripts/plot_sensitivity.py
};

// Every file a run writes into `dir`, figures included, for CheckOutputPaths
// before the run starts: a bad path then fails at once, not after a sweep
// of many minutes with the first files already in place.
std::vector<std::string> CalibrationOutputPaths(const std::string& dir, const std::vector<std::string>& sweep_suffixes);

// Writes the report's and every sweep's data files into `dir`, then draws
// every figure with `draw` (the sweeps' tornados, then the report's bars),
// and says on `log` what it wrote: "report  PATH", "data    PATH",
// "sweep   PATH", "flips   PATH", "plot    PATH", or for a figure not
// drawn "plot    not made here (WHY); run: COMMAND".
void WriteCalibrationOutputs(const std::string& dir, const CalibrationReport& report,
                             const std::vector<SweptColumn>& sweeps, const PlotScripts& scripts, const DrawFigure& draw,
                             std::ostream& log);

// Draws with /usr/bin/python3, which has the Debian matplotlib
// (scripts/setup); returns "" when drawn, otherwise why not: no python3,
// no script, or the script's last line of error output (a missing
// matplotlib reads "ModuleNotFoundError: No module named 'matplotlib'").
std::string DrawWithPython(const Figure& figure);
// The shell command DrawWithPython runs, for the user to run by hand.
std::string FigureCommand(const Figure& figure);

}  // namespace rc
