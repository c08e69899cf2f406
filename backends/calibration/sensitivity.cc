#include "backends/calibration/sensitivity.h"

#include <algorithm>
#include <cmath>
#include <ostream>
#include <stdexcept>

#include "common/input_error.h"
#include "traces/csv_table.h"

namespace rc {
namespace {

// Parameters issue #20 names among the assumptions every sweep must cover,
// by key or by the key's last part (both TTA+ and RoboCore have a warp
// buffer, for instance).
bool NamedByTheIssue(const std::string& key) {
  const std::string last = key.substr(key.rfind('.') + 1);
  for (const char* k : {"pre_process_initiation_cycles", "box_normal_initiation_cycles", "edge_edge_initiation_cycles",
                        "warp_buffer_warps", "sector_requests_per_cycle", "l1_sectors_per_cycle",
                        "op_units_per_kind_per_set", "kernel_launch_cycles", "program_config_cycles_per_micro_op",
                        "decode_config_cycles_per_layout", "precision", "isa"})
    if (last == k) return true;
  return false;
}

bool Flips(const SweptResult& r, double baseline, double measured) {
  return (baseline - r.neutral()) * (measured - r.neutral()) < 0;
}

}  // namespace

bool InQuickSubset(const ParameterVariants& parameter) {
  return NamedByTheIssue(parameter.key) || std::string(parameter.spec.source).rfind("assumption", 0) == 0;
}

Sensitivity SweepParametersTogether(const BackendParameters& base, const MeasureAllRows& measure_all,
                                    const SensitivityOptions& options) {
  Sensitivity s;
  struct Variant {
    std::string key, value;
  };
  std::vector<Variant> variants;
  std::vector<BackendParameters> parameter_sets = {base};
  for (const ParameterVariants& p : SweepVariants(base)) {
    if (options.quick && !InQuickSubset(p)) continue;
    std::vector<std::string> values = p.alternatives;
    if (options.artifact) {
      std::string theirs = ParameterValue(*options.artifact, p.key);
      const bool number = !theirs.empty() && (std::isdigit(static_cast<unsigned char>(theirs[0])) || theirs[0] == '-');
      if (!number) theirs = "\"" + theirs + "\"";
      if (ParameterValue(*options.artifact, p.key) != p.value &&
          std::find(values.begin(), values.end(), theirs) == values.end())
        values.push_back(theirs);
    }
    if (values.empty()) continue;
    ++s.parameters_swept;
    for (const std::string& v : values) {
      try {
        parameter_sets.push_back(WithParameter(base, p.key, v));
        variants.push_back({p.key, v});
      } catch (const InputError& e) {
        s.skipped.push_back(p.key + "=" + v + ": " + e.what());
      }
    }
  }
  const std::vector<std::vector<CalibrationRow>> measured = measure_all(parameter_sets);
  if (measured.size() != parameter_sets.size())
    throw std::logic_error("the sweep measured " + std::to_string(measured.size()) + " parameter sets of " +
                           std::to_string(parameter_sets.size()));
  for (const CalibrationRow& row : measured.front()) {
    s.results.push_back({row.result, row.unit});
    s.baseline.push_back(row.ours);
    s.points.push_back({s.results.size() - 1, "", "default", row.ours});
  }
  for (std::size_t v = 0; v < variants.size(); ++v) {
    const std::vector<CalibrationRow>& rows = measured[v + 1];
    const std::string what = variants[v].key + "=" + variants[v].value;
    if (rows.size() != s.results.size()) throw std::logic_error("the calibration rows changed with " + what);
    for (std::size_t r = 0; r < rows.size(); ++r) {
      if (rows[r].result != s.results[r].name)
        throw std::logic_error("the calibration rows changed order with " + what);
      s.points.push_back({r, variants[v].key, variants[v].value, rows[r].ours});
    }
  }
  return s;
}

Sensitivity SweepParameters(const BackendParameters& base, const MeasureRows& measure,
                            const SensitivityOptions& options) {
  return SweepParametersTogether(
      base,
      [&](const std::vector<BackendParameters>& sets) {
        std::vector<std::vector<CalibrationRow>> rows;
        for (const BackendParameters& p : sets) rows.push_back(measure(p));
        return rows;
      },
      options);
}

void WriteSensitivityCsv(const std::string& path, const Sensitivity& s) {
  CsvTableOptions options;
  options.significant_digits = 6;
  CsvTable table(path, {"ratio", "parameter", "value", "result"}, options);
  for (const SensitivityPoint& p : s.points)
    table.AddRow({s.results[p.result].name, p.parameter, p.value,
                  std::isnan(p.measured) ? CsvCell::Empty() : CsvCell(p.measured)});
  table.Commit();
}

void WriteFlipTable(std::ostream& out, const Sensitivity& s) {
  out << "| result | ours (default) | parameter | value | result then |\n|---|---|---|---|---|\n";
  std::vector<int> flips(s.results.size(), 0);
  for (const SensitivityPoint& p : s.points) {
    if (p.parameter.empty()) continue;
    const SweptResult& r = s.results[p.result];
    if (!Flips(r, s.baseline[p.result], p.measured)) continue;
    ++flips[p.result];
    out << "| " << r.name << " | " << FormatValue(s.baseline[p.result], r.unit) << " | `" << p.parameter << "` | "
        << p.value << " | " << FormatValue(p.measured, r.unit) << " |\n";
  }
  out << "\n";
  for (std::size_t r = 0; r < s.results.size(); ++r)
    out << "- " << s.results[r].name << ": "
        << (flips[r] ? std::to_string(flips[r]) + " variant(s) flip it" : std::string("no variant flips it")) << " ("
        << s.parameters_swept << " parameters swept)\n";
}

std::vector<ResultRange> RangesOf(const Sensitivity& s) {
  std::vector<ResultRange> ranges(s.results.size());
  for (std::size_t r = 0; r < s.results.size(); ++r) ranges[r].low = ranges[r].high = s.baseline[r];
  for (const SensitivityPoint& p : s.points) {
    if (std::isnan(p.measured)) continue;
    ResultRange& range = ranges[p.result];
    if (p.measured < range.low) {
      range.low = p.measured;
      range.low_parameter = p.parameter + "=" + p.value;
    }
    if (p.measured > range.high) {
      range.high = p.measured;
      range.high_parameter = p.parameter + "=" + p.value;
    }
  }
  return ranges;
}

}  // namespace rc
