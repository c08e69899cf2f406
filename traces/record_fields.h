#pragma once
// Validation shared by the trace readers, so that every format reports the
// same problems the same way: InputError with file, 1-based line and a field
// name a user can find in the line ("range 37", "ts", "theta").
#include <cstddef>
#include <functional>
#include <string>
#include <string_view>

#include "common/text_fields.h"
#include "traces/sensor_trace.h"

namespace rc {

// Names the field at a 0-based position of a record layout.
using FieldNamer = std::function<std::string(std::size_t index)>;

// Throws unless a record has exactly `expected` fields. A short line names the
// first missing field (a line cut off mid-scan says which range is missing);
// `layout` is the record's format as a reader would write it in a manual.
void RequireFieldCount(const LineReader& reader, std::size_t actual, std::size_t expected, const FieldNamer& name_of,
                       const std::string& layout);

// "range 1" .. "range N": 1-based like the r1..r180 of the CMU format note.
std::string RangeFieldName(std::size_t beam_index);

// Parses one range reading given in a unit of which `units_per_metre` make a
// metre (100 for cm, 1 for m; dividing keeps cm -> m correctly rounded).
// Rejected: non-numeric, NaN, inf, negative. Accepted: 0 (no log in
// shared/data contains one, but drivers such as CARMEN's use 0 for "no
// echo"; the sensor model, not the reader, decides what a 0 means).
// Readings at or beyond the no-return threshold are kept as logged.
float ParseRange(const LineReader& reader, std::string_view token, std::size_t beam_index, double units_per_metre);

// Laser records must be in time order: the motion model differences
// consecutive records, and a step far back means a spliced or corrupt log.
// Equal times are allowed (RoWild logs have no timestamps at all).
//
// A small step back is a clock glitch of a real log, not corruption: the
// Intel Research Lab's corrected CARMEN log steps back by 0.1 s once. Such a
// record is kept as logged (the motion model uses poses, not times) and
// counted; the command line prints the count as a warning. Only a step back
// of kMaxClockGlitchS or more is an InputError.
//
// kMaxClockGlitchS: 0.5 s, range (0, 1] s. Source: five times the Intel log's
// 0.1 s glitch, and several scan periods of any 2D laser logged here (SICK
// LMS at 5-75 Hz), so a larger step cannot be timestamp jitter of one scan.
inline constexpr double kMaxClockGlitchS = 0.5;

struct TimeGlitchStats {
  long count = 0;               // laser records earlier than the one before
  double largest_step_s = 0.0;  // the largest such step back (s)
  long first_line = 0;          // 1-based line of the first one (0: none)
};

class LaserTimeOrder {
 public:
  void Check(const LineReader& reader, double time_s, const std::string& field);
  const TimeGlitchStats& glitches() const { return glitches_; }

 private:
  bool has_previous_ = false;
  double previous_s_ = 0.0;
  long previous_line_ = 0;
  TimeGlitchStats glitches_;
};

// A trace without laser records cannot drive MCL: throws InputError for the
// whole file (line 0) naming the record kind that was missing.
void RequireLaserRecords(const SensorTrace& trace, const std::string& record_kind);
void RequireLaserRecords(const std::string& path, std::size_t count, const std::string& record_kind);

}  // namespace rc
