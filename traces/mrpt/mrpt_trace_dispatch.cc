#include "traces/mrpt/mrpt_trace_dispatch.h"

#include "common/file_names.h"
#include "common/input_error.h"

namespace rc {

bool HasRawlogExtension(const std::string& path) {
  return FileNameEndsWith(path, ".rawlog") || FileNameEndsWith(path, ".rawlog.gz");
}

std::string TraceFormatNamesWithRawlog() { return "auto, cmu, rowild, carmen or rawlog"; }

SensorTrace ReadTraceWithRawlog(const std::string& path, const TraceReadOptions& options,
                                const RawlogReadOptions& rawlog, TraceReadStats* stats) {
  const bool is_rawlog = options.format == "rawlog" || (options.format == "auto" && HasRawlogExtension(path));
  if (!is_rawlog) {
    if (options.format != "auto" && options.format != "cmu" && options.format != "rowild" && options.format != "carmen")
      throw UsageError("unknown trace format '" + options.format + "' (expected " + TraceFormatNamesWithRawlog() + ")");
    return ReadTrace(path, options, stats);
  }
  if (options.expected_beam_count < 0)
    throw UsageError("expected beam count must be >= 0 (0 = take it from the format)");
  SensorTrace trace = ReadMrptRawlog(path, rawlog, stats);
  if (options.expected_beam_count != 0 && trace.geometry.beam_count != options.expected_beam_count)
    throw InputError(path, 0, "beam count",
                     "the rawlog has " + std::to_string(trace.geometry.beam_count) + " beams per scan, expected " +
                         std::to_string(options.expected_beam_count));
  ApplyLaserOffset(options, trace.geometry);
  return trace;
}

std::unique_ptr<ScanSource> OpenTraceStreamWithRawlog(const std::string& path, const TraceReadOptions& options,
                                                      const RawlogReadOptions& rawlog, TraceReadStats* stats) {
  const bool is_rawlog = options.format == "rawlog" || (options.format == "auto" && HasRawlogExtension(path));
  if (!is_rawlog) {
    if (options.format != "auto" && options.format != "cmu" && options.format != "rowild" && options.format != "carmen")
      throw UsageError("unknown trace format '" + options.format + "' (expected " + TraceFormatNamesWithRawlog() + ")");
    return OpenTraceStream(path, options, stats);
  }
  return std::make_unique<OwningScanSource>(ReadTraceWithRawlog(path, options, rawlog, stats));
}

}  // namespace rc
