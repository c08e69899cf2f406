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

}  // namespace

const char* ToString(CalibrationUnit unit) {
  switch (unit) {
    case CalibrationUnit::kSpeedup: return "x faster";
    case CalibrationUnit::kPercentChange: return "% change";
  }
  return "?";
}

double Speedup(double baseline_seconds, double variant_seconds) { return baseline_seconds / variant_seconds; }

double PercentChange(double base, double variant) { return 100.0 * (variant - base) / base; }

std::string FormatSentence(const char* format, ...) {
  char buf[600];
  va_list args;
  va_start(args, format);
  std::vsnprintf(buf, sizeof buf, format, args);
  va_end(args);
  return buf;
}

std::string FormatValue(double value, CalibrationUnit unit) {
  if (std::isnan(value)) return "-";
  char buf[48];
  if (unit == CalibrationUnit::kSpeedup && value >= 1.0)
    std::snprintf(buf, sizeof buf, "%.2fx faster", value);
  else if (unit == CalibrationUnit::kSpeedup)
    std::snprintf(buf, sizeof buf, "%.2fx (%.2fx slower)", value, 1.0 / value);
  else
    std::snprintf(buf, sizeof buf, "%+.1f%%", value);
  return buf;
}

void WriteCalibrationMarkdown(std::ostream& out, const CalibrationReport& report) {
  out << "# Calibration: the RoboGPU paper's reported results beside ours\n\n"
      << "Ours come from pricing recorded workloads in one run (`rcbench calibrate`); no constant was tuned toward\n"
      << "a paper value. Speedups are baseline time / our time; percent changes are (variant - base) / base.\n\n";
  for (const std::string& note : report.workload_notes) out << "- " << note << "\n";
  out << "\n| result | paper | ours | why ours differs |\n|---|---|---|---|\n";
  for (const CalibrationRow& r : report.rows)
    out << "| " << Cell(r.result) << " | " << Cell(r.paper) << " | " << FormatValue(r.ours, r.unit) << " | "
        << Cell(r.why) << " |\n";
}

void WriteCalibrationCsv(std::ostream& out, const CalibrationReport& report) {
  out << "result,unit,paper_value,ours\n";
  for (const CalibrationRow& r : report.rows)
    out << CsvField(r.result) << ',' << ToString(r.unit) << ',' << Number(r.paper_value) << ',' << Number(r.ours)
        << '\n';
}

}  // namespace rc
