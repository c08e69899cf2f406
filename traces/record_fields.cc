#include "traces/record_fields.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

namespace rc {

void RequireFieldCount(const LineReader& reader, std::size_t actual, std::size_t expected, const FieldNamer& name_of,
                       const std::string& layout) {
  if (actual < expected)
    reader.Fail(name_of(actual), "line ends after " + std::to_string(actual) + " of " + std::to_string(expected) +
                                     " fields (" + layout + ")");
  if (actual > expected)
    reader.Fail("field " + std::to_string(expected + 1), std::to_string(actual) + " fields where " +
                                                             std::to_string(expected) + " were expected (" + layout +
                                                             ")");
}

std::string RangeFieldName(std::size_t beam_index) { return "range " + std::to_string(beam_index + 1); }

float ParseRange(const LineReader& reader, std::string_view token, std::size_t beam_index, double units_per_metre) {
  const std::string field = RangeFieldName(beam_index);
  const double value = reader.ParseDouble(token, field);  // rejects NaN and inf
  if (value < 0.0) reader.Fail(field, "negative range '" + std::string(token) + "'");
  const double metres = value / units_per_metre;
  if (metres > std::numeric_limits<float>::max())
    reader.Fail(field, "range '" + std::string(token) + "' is too large to store");
  return static_cast<float>(metres);
}

void LaserTimeOrder::Check(const LineReader& reader, double time_s, const std::string& field) {
  if (has_previous_ && time_s < previous_s_) {
    const double step_s = previous_s_ - time_s;
    if (!(step_s < kMaxClockGlitchS)) {
      reader.Fail(field, fmt::format("time {:.6f} s is {:.6f} s earlier than {:.6f} s of the laser record on line {} "
                                     "(a step back of {:.1f} s or more is not a clock glitch)",
                                     time_s, step_s, previous_s_, previous_line_, kMaxClockGlitchS));
    }
    if (glitches_.count == 0) glitches_.first_line = reader.line_number();
    ++glitches_.count;
    glitches_.largest_step_s = std::max(glitches_.largest_step_s, step_s);
  }
  has_previous_ = true;
  previous_s_ = time_s;
  previous_line_ = reader.line_number();
}

void RequireLaserRecords(const std::string& path, std::size_t count, const std::string& record_kind) {
  if (count == 0)
    throw InputError(path, 0, record_kind,
                     "the trace has no laser records (" + record_kind + "), nothing to localize with");
}

void RequireLaserRecords(const SensorTrace& trace, const std::string& record_kind) {
  RequireLaserRecords(trace.source_path, trace.scans.size(), record_kind);
}

}  // namespace rc
