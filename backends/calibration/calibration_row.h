#pragma once
// One line of the calibration report (`rcbench calibrate`): a result the
// RoboGPU paper reports (REFERENCE.md section 1, "Reported results") beside
// the same quantity measured by pricing our own recorded workloads twice,
// under the artifact preset (backends/presets/artifact.json) and under our
// defaults, with the workload's size and one sentence on why ours differs.
// Nothing here is a target: the paper's value is only printed next to ours
// (REFERENCE.md: "None of them is a target to tune constants to").
#include <cmath>
#include <iosfwd>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace rc {

// How a row's number reads, so the paper's and ours compare like for like.
enum class CalibrationUnit {
  kSpeedup,        // "x faster": baseline time / our time (> 1 = faster)
  kPercentChange,  // signed %: (variant - base) / base x 100 (negative = less)
};
const char* ToString(CalibrationUnit unit);  // "x faster" | "% change"

// The spread a sensitivity sweep found for a measured value (in the row's
// unit): the lowest and highest value over the swept parameters. Filled by
// the sweep (backends/calibration/sensitivity.h), absent otherwise.
struct ValueRange {
  double low = std::numeric_limits<double>::quiet_NaN();
  double high = std::numeric_limits<double>::quiet_NaN();
};

// Which workload scale a row measures.
enum class CalibrationScale {
  kPaperScale,  // octrees of 1000-2000 nodes and >= 10,000 queries; whole DeliBot runs
  kSmallBatch,  // one DeliBot update; 70 OBBs against a 107-node tree
};
const char* ToString(CalibrationScale scale);  // "paper scale" | "small batch"

struct CalibrationRow {
  std::string result;  // what is compared, e.g. "SACT collision queries, RoboCore vs CUDA"
  CalibrationScale scale = CalibrationScale::kPaperScale;
  std::string workload;  // its size: queries, nodes per query, tree nodes, updates
  std::string paper;     // the paper's statement, as it words it
  double paper_value = std::numeric_limits<double>::quiet_NaN();  // in `unit`; NaN: no number given
  double artifact = std::numeric_limits<double>::quiet_NaN();     // in `unit`, priced under the artifact preset
  double ours = std::numeric_limits<double>::quiet_NaN();         // in `unit`, priced under our parameters
  std::optional<ValueRange> artifact_range;                       // the sensitivity sweep's, when run
  std::optional<ValueRange> ours_range;
  CalibrationUnit unit = CalibrationUnit::kSpeedup;
  std::string why;  // computed from the run: what limits each side (why_sentences.h)
};

// What one calibration run measured on, for the report's header.
struct CalibrationReport {
  std::vector<std::string> workload_notes;  // one line per workload (map, batch, scene)
  std::string ours_name;                    // "default", or the --params file
  std::vector<CalibrationRow> rows;
};

// One column's measurement of a row: the value, the why sentence computed
// from that column's run, and what limited it (a LimitTag list), so that
// the row can say when the other column's run was limited by something else.
struct ColumnValue {
  double value = std::numeric_limits<double>::quiet_NaN();
  std::string why;
  std::string limits;
};
// Sets row.artifact and row.ours, and row.why: ours' sentence, followed by
// what limited the artifact preset's run when that differs from ours.
void SetColumns(CalibrationRow& row, const ColumnValue& artifact, const ColumnValue& ours);

// Speedup of `variant` over `baseline` from their times (baseline / variant).
double Speedup(double baseline_seconds, double variant_seconds);
// Signed percent change of `variant` against `base`.
double PercentChange(double base, double variant);

// "13.3x faster" style text of a value in a unit ("-" for NaN), with the
// range in parentheses when given.
std::string FormatValue(double value, CalibrationUnit unit, const std::optional<ValueRange>& range = std::nullopt);

// The Markdown report: the workload notes, then per scale a table
// | result | workload | paper | artifact preset | ours | why ours differs |.
void WriteCalibrationMarkdown(std::ostream& out, const CalibrationReport& report);
// The plot's input, written to `path` atomically (traces/csv_table.h):
// result,scale,unit,workload,paper_value,artifact,ours,artifact_low,
// artifact_high,ours_low,ours_high (4 significant digits; empty for NaN or
// no range). Throws OutputError when the file cannot be written.
void WriteCalibrationCsv(const std::string& path, const CalibrationReport& report);

}  // namespace rc
