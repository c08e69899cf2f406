#include "backends/calibration/calibration_row.h"

#include <cstdarg>
#include <cstdio>
#include <ostream>

namespace rc {
namespace {

// Markdown table cells may not hold a raw '|'.
std::string Cell(const std::string& text) {
  std::string out;
  for (char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

// CSV fields are quoted when they hold a comma or a quote.
std::string CsvField(const std::string& text) {
  if (text.find_first_of(",\"") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string Number(double value) {
  if (std::isnan(value)) return "";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", value);
  return buf;
}

std::string RangeFields(const std::optional<ValueRange>& range) {
  return range ? Number(range->low) + "," + Number(range->high) : std::string(",");
}

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

std::string FormatSentence(const char* format, ...) {
  char buf[1000];
  va_list args;
  va_start(args, format);
  std::vsnprintf(buf, sizeof buf, format, args);
  va_end(args);
  return buf;
}

std::string FormatValue(double value, CalibrationUnit unit, const std::optional<ValueRange>& range) {
  if (std::isnan(value)) return "-";
  char buf[64];
  if (unit == CalibrationUnit::kSpeedup && value >= 1.0)
    std::snprintf(buf, sizeof buf, "%.2fx faster", value);
  else if (unit == CalibrationUnit::kSpeedup)
    std::snprintf(buf, sizeof buf, "%.2fx (%.2fx slower)", value, 1.0 / value);
  else
    std::snprintf(buf, sizeof buf, "%+.1f%%", value);
  std::string text = buf;
  if (range) {
    const char* f = unit == CalibrationUnit::kSpeedup ? " (%.2f-%.2fx)" : " (%+.1f to %+.1f%%)";
    std::snprintf(buf, sizeof buf, f, range->low, range->high);
    text += buf;
  }
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

void WriteCalibrationCsv(std::ostream& out, const CalibrationReport& report) {
  out << "result,scale,unit,workload,paper_value,artifact,ours,artifact_low,artifact_high,ours_low,ours_high\n";
  for (const CalibrationRow& r : report.rows)
    out << CsvField(r.result) << ',' << ToString(r.scale) << ',' << ToString(r.unit) << ',' << CsvField(r.workload)
        << ',' << Number(r.paper_value) << ',' << Number(r.artifact) << ',' << Number(r.ours) << ','
        << RangeFields(r.artifact_range) << ',' << RangeFields(r.ours_range) << '\n';
}

}  // namespace rc
