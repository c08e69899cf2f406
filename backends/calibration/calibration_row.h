#pragma once
// One line of the calibration report (`rcbench calibrate`): a result the
// RoboGPU paper reports (REFERENCE.md section 1, "Reported results") beside
// the same quantity measured by pricing our own recorded workloads, with one
// sentence on why ours differs. Nothing here is a target: the paper's value
// is only printed next to ours (REFERENCE.md: "None of them is a target to
// tune constants to").
#include <cmath>
#include <iosfwd>
#include <limits>
#include <string>
#include <vector>

namespace rc {

// How a row's number reads, so the paper's and ours compare like for like.
enum class CalibrationUnit {
  kSpeedup,        // "x faster": baseline time / our time (> 1 = faster)
  kPercentChange,  // signed %: (variant - base) / base x 100 (negative = less)
};
const char* ToString(CalibrationUnit unit);  // "x faster" | "% change"

struct CalibrationRow {
  std::string result;  // what is compared, e.g. "SACT collision queries, RoboCore vs CUDA"
  std::string paper;   // the paper's statement, as it words it
  double paper_value = std::numeric_limits<double>::quiet_NaN();  // in `unit`; NaN: no number given
  double ours = std::numeric_limits<double>::quiet_NaN();         // in `unit`, from pricing
  CalibrationUnit unit = CalibrationUnit::kSpeedup;
  std::string why;     // one sentence: why ours differs (mechanism, not tuning)
};

// What one calibration run measured on, for the report's header.
struct CalibrationReport {
  std::vector<std::string> workload_notes;  // one line per workload (map, batch, scene)
  std::vector<CalibrationRow> rows;
};

// Speedup of `variant` over `baseline` from their times (baseline / variant).
double Speedup(double baseline_seconds, double variant_seconds);
// Signed percent change of `variant` against `base`.
double PercentChange(double base, double variant);

// printf-style text for a row's `why` sentence (up to 600 characters).
std::string FormatSentence(const char* format, ...) __attribute__((format(printf, 1, 2)));

// "13.3x faster" style text of a value in a unit ("-" for NaN).
std::string FormatValue(double value, CalibrationUnit unit);

// The Markdown report: the workload notes, then a table
// | result | paper | ours | why ours differs |.
void WriteCalibrationMarkdown(std::ostream& out, const CalibrationReport& report);
// The plot's input: result,unit,paper_value,ours (empty paper_value for NaN).
void WriteCalibrationCsv(std::ostream& out, const CalibrationReport& report);

}  // namespace rc
