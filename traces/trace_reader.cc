#include "traces/trace_reader.h"

#include <cstdlib>
#include <fstream>

#include "common/text_fields.h"
#include "traces/rowild_log_reader.h"

namespace rc {
namespace {

constexpr std::size_t kRowildFields = 183;

bool IsNumber(std::string_view token) {
  const std::string text(token);
  char* end = nullptr;
  std::strtod(text.c_str(), &end);
  return !text.empty() && end == text.c_str() + text.size();
}

// Messages CARMEN's logger documents; enough to recognise a CARMEN log by its
// first message without mistaking other upper-case text for one.
bool IsKnownCarmenMessage(std::string_view token) {
  static const char* const kNames[] = {"PARAM",       "SYNC",        "ODOM",      "TRUEPOS",
                                       "FLASER",      "RLASER",      "LASER3",    "LASER4",
                                       "RAWLASER1",   "RAWLASER2",   "RAWLASER3", "RAWLASER4",
                                       "ROBOTLASER1", "ROBOTLASER2", "NMEAGGA",   "NMEARMC"};
  for (const char* name : kNames)
    if (token == name) return true;
  return false;
}

}  // namespace

std::string DetectTraceFormat(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "", "cannot open trace file");
  LineReader reader(in, path);
  std::string line;
  while (reader.Next(line)) {
    const auto fields = SplitFields(line);
    if (fields.empty()) continue;
    if (fields[0][0] == '#') return "carmen";
    if (fields[0] == "O" || fields[0] == "L") return "cmu";
    if (IsKnownCarmenMessage(fields[0])) return "carmen";
    if (fields.size() == kRowildFields) {
      for (std::size_t i = 0; i < fields.size(); ++i)
        if (!IsNumber(fields[i])) reader.Fail("field " + std::to_string(i + 1),
                                              "looks like a RoWild log (183 fields) but '" +
                                                  std::string(fields[i]) + "' is not a number");
      return "rowild";
    }
    reader.Fail("format", "cannot tell the trace format from this line (" + std::to_string(fields.size()) +
                              " fields starting with '" + std::string(fields[0]) +
                              "'); expected CMU O/L records, CARMEN messages or RoWild's 183 numbers; "
                              "name the format explicitly");
  }
  throw InputError(path, 0, "format", "the file is empty: no records to detect a format from");
}

SensorTrace ReadTrace(const std::string& path, const TraceReadOptions& options, TraceReadStats* stats) {
  const std::string& requested = options.format;
  if (requested != "auto" && requested != "cmu" && requested != "rowild" && requested != "carmen")
    throw UsageError("unknown trace format '" + requested + "' (expected auto, cmu, rowild or carmen)");
  if (options.expected_beam_count < 0)
    throw UsageError("expected beam count must be >= 0 (0 = take it from the format)");
  const std::string format = requested == "auto" ? DetectTraceFormat(path) : requested;

  if (options.laser_offset_forward_m && !(*options.laser_offset_forward_m >= 0.0 && *options.laser_offset_forward_m <= 10.0))
    throw UsageError("--laser-offset must be in [0, 10] m");
  CmuLogOptions cmu = options.cmu;
  CarmenLogOptions carmen = options.carmen;
  if (options.laser_offset_forward_m) cmu.laser_offset_forward_m = carmen.laser_offset_forward_m = options.laser_offset_forward_m;
  SensorTrace trace;
  if (format == "cmu") trace = ReadCmuLog(path, cmu, stats);
  else if (format == "rowild") trace = ReadRowildLog(path, stats);
  else trace = ReadCarmenLog(path, carmen, stats);
  if (options.laser_offset_forward_m) trace.geometry.offset_forward_m = *options.laser_offset_forward_m;

  if (options.expected_beam_count != 0 && trace.geometry.beam_count != options.expected_beam_count)
    throw InputError(path, trace.scans.front().source_line, "beam count",
                     "the " + format + " trace has " + std::to_string(trace.geometry.beam_count) +
                         " beams per scan, expected " + std::to_string(options.expected_beam_count));
  return trace;
}

}  // namespace rc
