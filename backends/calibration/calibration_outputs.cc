#include "backends/calibration/calibration_outputs.h"

#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <ostream>

#include "common/atomic_file.h"

namespace rc {
namespace {

const char* const kPython = "/usr/bin/python3";

std::string InDir(const std::string& dir, const std::string& name) { return dir + "/" + name; }

// A swept column's file: DIR/<stem><suffix>.<extension>, the one place its
// names are made (the output check and the writer both use it).
std::string ColumnFile(const std::string& dir, const char* stem, const std::string& suffix, const char* extension) {
  return InDir(dir, stem + suffix + "." + extension);
}

template <class Write>
void WriteFile(const std::string& path, Write write) {
  AtomicFile file(path);
  write(file.stream());
  file.Commit();
}

// Single-quoted for /bin/sh.
std::string ShellQuote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

}  // namespace

std::vector<std::string> CalibrationOutputPaths(const std::string& dir,
                                                const std::vector<std::string>& sweep_suffixes) {
  std::vector<std::string> paths = {InDir(dir, "calibration.md"), InDir(dir, "calibration.csv"),
                                    InDir(dir, "calibration.png")};
  for (const std::string& s : sweep_suffixes)
    paths.insert(paths.end(), {ColumnFile(dir, "sensitivity", s, "csv"), ColumnFile(dir, "flips", s, "md"),
                               ColumnFile(dir, "sensitivity", s, "png")});
  return paths;
}

void WriteCalibrationOutputs(const std::string& dir, const CalibrationReport& report,
                             const std::vector<SweptColumn>& sweeps, const PlotScripts& scripts, const DrawFigure& draw,
                             std::ostream& log) {
  // Every data file before any figure: plot_sensitivity.py reads calibration.csv.
  const std::string md = InDir(dir, "calibration.md"), csv = InDir(dir, "calibration.csv");
  WriteFile(md, [&](std::ostream& out) { WriteCalibrationMarkdown(out, report); });
  WriteCalibrationCsv(csv, report);
  log << "report  " << md << "\ndata    " << csv << "\n";
  std::vector<Figure> figures;
  for (const SweptColumn& column : sweeps) {
    const std::string sweep = ColumnFile(dir, "sensitivity", column.suffix, "csv");
    const std::string flips = ColumnFile(dir, "flips", column.suffix, "md");
    WriteSensitivityCsv(sweep, column.sweep);
    WriteFile(flips, [&](std::ostream& out) { WriteFlipTable(out, column.sweep); });
    log << "sweep   " << sweep << "\nflips   " << flips << "\n";
    figures.push_back({scripts.sensitivity, sweep, ColumnFile(dir, "sensitivity", column.suffix, "png")});
  }
  figures.push_back({scripts.calibration, csv, InDir(dir, "calibration.png")});
  for (const Figure& figure : figures) {
    const std::string why_not = draw(figure);
    if (why_not.empty())
      log << "plot    " << figure.png << "\n";
    else
      log << "plot    not made here (" << why_not << "); run: " << FigureCommand(figure) << "\n";
  }
}

std::string FigureCommand(const Figure& figure) {
  return std::string(kPython) + " " + ShellQuote(figure.script) + " " + ShellQuote(figure.input) + " " +
         ShellQuote(figure.png);
}

std::string DrawWithPython(const Figure& figure) {
  if (!std::filesystem::exists(kPython)) return std::string("no ") + kPython;
  if (!std::filesystem::exists(figure.script)) return "no " + figure.script;
  // The script's own output is dropped; its error output is kept for the why.
  FILE* pipe = ::popen((FigureCommand(figure) + " 2>&1 >/dev/null").c_str(), "r");
  if (pipe == nullptr) return "could not start " + std::string(kPython);
  std::string errors;
  char buffer[4096];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) errors.append(buffer, n);
  const int status = ::pclose(pipe);
  if (status != -1 && WIFEXITED(status) && WEXITSTATUS(status) == 0) return "";
  while (!errors.empty() && (errors.back() == '\n' || errors.back() == ' ')) errors.pop_back();
  const std::size_t last_line = errors.rfind('\n');
  const std::string last = last_line == std::string::npos ? errors : errors.substr(last_line + 1);
  return "the script failed" + (last.empty() ? std::string() : ": " + last);
}

}  // namespace rc
