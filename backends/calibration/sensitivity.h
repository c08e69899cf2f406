#pragma once
// How robust each calibration conclusion is (`rcbench calibrate
// --sensitivity`): every declared cost-model parameter is moved, one at a
// time with the others at their defaults, over x0.5 and x2 of its value
// (within its declared range), over every other value of a choice, and to
// the RoboGPU artifact's value where the artifact preset sets one; each
// headline result is re-measured on the same recorded workloads. A result
// "flips" when a variant puts it on the other side of its neutral point (a
// speedup across 1, a percent change across 0).
//
//   DIR/sensitivity.csv   ratio,parameter,value,result (one row per
//                         result x variant; value "default" is the
//                         baseline)
//   DIR/flips.md          the parameters whose range flips a result
//   DIR/sensitivity.png   a tornado plot per result (scripts/plot_sensitivity.py)
#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

#include "backends/backend_params.h"
#include "backends/calibration/calibration_row.h"

namespace rc {

// A result the sweep follows, and where it flips.
struct SweptResult {
  std::string name;
  CalibrationUnit unit = CalibrationUnit::kSpeedup;
  double neutral() const { return unit == CalibrationUnit::kSpeedup ? 1.0 : 0.0; }
};

struct SensitivityPoint {
  std::size_t result = 0;  // index into Sensitivity::results
  std::string parameter;   // "robocore.warp_buffer_warps"; empty for the baseline
  std::string value;       // JSON text of the value tried; "default" for the baseline
  double measured = 0.0;
};

struct Sensitivity {
  std::vector<SweptResult> results;
  std::vector<double> baseline;          // per result
  std::vector<SensitivityPoint> points;  // baseline first, then every variant
  std::vector<std::string> skipped;      // "key=value: why" (a variant the checks refuse)
  std::size_t parameters_swept = 0;
};

struct SensitivityOptions {
  // Only the parameters whose source is an assumption, plus the ones issue
  // #20 names (SACT initiation, warp buffer, L1 requests per cycle, OP units
  // per kind, launch and configuration cycles, precision and ISA): the
  // subset CI can afford.
  bool quick = false;
  // The artifact preset's parameters, when known: a parameter whose value
  // there differs from ours is also tried at the artifact's value.
  const BackendParameters* artifact = nullptr;
};

// `measure` prices the workloads under the given parameters and returns
// every calibration row; the rows' results and units must not depend on
// the parameters.
using MeasureRows = std::function<std::vector<CalibrationRow>(const BackendParameters&)>;

Sensitivity SweepParameters(const BackendParameters& base, const MeasureRows& measure,
                            const SensitivityOptions& options = {});
// The same, with every parameter set measured in one call (the baseline
// first, then each variant the parameter checks accept): for workloads
// that price many parameter sets more cheaply together than one by one
// (a whole DeliBot run, filtered once and priced under every variant).
// Returns one row list per parameter set, in the order given.
using MeasureAllRows =
    std::function<std::vector<std::vector<CalibrationRow>>(const std::vector<BackendParameters>& parameter_sets)>;
Sensitivity SweepParametersTogether(const BackendParameters& base, const MeasureAllRows& measure_all,
                                    const SensitivityOptions& options = {});

// Whether the parameter is in the quick subset.
bool InQuickSubset(const ParameterVariants& parameter);

// Every swept point as a CSV row, written to `path` atomically
// (traces/csv_table.h): ratio,parameter,value,result (6 significant digits;
// empty when the point could not be measured).
void WriteSensitivityCsv(const std::string& path, const Sensitivity& sensitivity);
// A Markdown table of every (result, parameter) whose variants flip the
// result, with the baseline and the flipping value and result; and a line
// per result saying whether anything flips it.
void WriteFlipTable(std::ostream& out, const Sensitivity& sensitivity);
// Per result: the lowest and highest value any variant gives, and which
// parameter gives each (for the calibration table's range column).
struct ResultRange {
  double low = 0.0, high = 0.0;
  std::string low_parameter, high_parameter;
};
std::vector<ResultRange> RangesOf(const Sensitivity& sensitivity);

}  // namespace rc
