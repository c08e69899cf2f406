#include "backends/calibration/calibration_row.h"

#include <ostream>

#include <fmt/format.h>

#include "traces/csv_table.h"

namespace rc {
namespace {

// Markdown table cells may not hold a raw '|'.
std::string Cell(const std::string& text) {
  std::string out;
  for (char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

// A measured value for the CSV, or an empty cell for "no number".
CsvCell ValueCell(double value) { return std::isnan(value) ? CsvCell::Empty() : CsvCell(value); }

}  // namespace

const char* ToString(CalibrationUnit unit) {
  switch (unit) {
    case CalibrationUnit::kSpeedup: return "x faster";
    case CalibrationUnit::kPercentChange: return "% change";
  }
  return "?";
}

const char* ToString(CalibrationScale scale) {
  return scale == CalibrationScale::kPaperScale ? "paper scale" : "small batch";
}

void SetColumns(CalibrationRow& row, const ColumnValue& artifact, const ColumnValue& ours) {
  row.artifact = artifact.value;
  row.ours = ours.value;
  row.why = ours.why;
  if (!artifact.limits.empty() && artifact.limits != ours.limits)
    row.why += " Under the artifact preset, " + artifact.limits + ".";
}

double Speedup(double baseline_seconds, double variant_seconds) { return baseline_seconds / variant_seconds; }

double PercentChange(double base, double variant) { return 100.0 * (variant - base) / base; }

std::string FormatValue(double value, CalibrationUnit unit, const std::optional<ValueRange>& range) {
  if (std::isnan(value)) return "-";
  std::string text;
  if (unit == CalibrationUnit::kSpeedup && value >= 1.0)
    text = fmt::format("{:.2f}x faster", value);
  else if (unit == CalibrationUnit::kSpeedup)
    text = fmt::format("{:.2f}x ({:.2f}x slower)", value, 1.0 / value);
  else
    text = fmt::format("{:+.1f}%", value);
  if (range && unit == CalibrationUnit::kSpeedup)
    text += fmt::format(" ({:.2f}-{:.2f}x)", range->low, range->high);
  else if (range)
    text += fmt::format(" ({:+.1f} to {:+.1f}%)", range->low, range->high);
  return text;
}

void WriteCalibrationMarkdown(std::ostream& out, const CalibrationReport& report) {
  out << "# Calibration: the RoboGPU paper's reported results beside ours\n\n"
      << "Ours come from pricing recorded workloads in one run (`rcbench calibrate`), twice: under the artifact\n"
      << "preset (the RoboGPU artifact's own configuration, backends/presets/artifact.json) and under our\n"
      << "parameters (" << report.ours_name << "). No constant was tuned toward a paper value. Speedups are\n"
      << "baseline time / our time; percent changes are (variant - base) / base. The why column is chosen by\n"
      << "what the run measured (what limits each side), for our parameters.\n\n";
  for (const std::string& note : report.workload_notes) out << "- " << note << "\n";
  for (CalibrationScale scale : {CalibrationScale::kPaperScale, CalibrationScale::kSmallBatch}) {
    bool any = false;
    for (const CalibrationRow& r : report.rows) any = any || r.scale == scale;
    if (!any) continue;
    out << "\n## " << (scale == CalibrationScale::kPaperScale ? "Paper scale" : "Small batch (kept for comparison)")
        << "\n\n| result | workload | paper | artifact preset | ours | why ours differs |\n|---|---|---|---|---|---|\n";
    for (const CalibrationRow& r : report.rows) {
      if (r.scale != scale) continue;
      out << "| " << Cell(r.result) << " | " << Cell(r.workload) << " | " << Cell(r.paper) << " | "
          << FormatValue(r.artifact, r.unit, r.artifact_range) << " | " << FormatValue(r.ours, r.unit, r.ours_range)
          << " | " << Cell(r.why) << " |\n";
    }
  }
}

void WriteCalibrationCsv(const std::string& path, const CalibrationReport& report) {
  CsvTableOptions options;
  options.significant_digits = 4;
  CsvTable table(path,
                 {"result", "scale", "unit", "workload", "paper_value", "artifact", "ours", "artifact_low",
                  "artifact_high", "ours_low", "ours_high"},
                 options);
  const ValueRange none;
  for (const CalibrationRow& r : report.rows) {
    const ValueRange& artifact = r.artifact_range.value_or(none);
    const ValueRange& ours = r.ours_range.value_or(none);
    table.AddRow({r.result, ToString(r.scale), ToString(r.unit), r.workload, ValueCell(r.paper_value),
                  ValueCell(r.artifact), ValueCell(r.ours), ValueCell(artifact.low), ValueCell(artifact.high),
                  ValueCell(ours.low), ValueCell(ours.high)});
  }
  table.Commit();
}

}  // namespace rc
