#pragma once
// ReadTrace plus MRPT's .rawlog. The rawlog reader needs MRPT, and rc_traces
// (layer 0, linked by every target) must not, so the format is registered
// here, one level up, and the command line calls this instead of ReadTrace.
//
// Format "rawlog", or "auto" with a .rawlog / .rawlog.gz name, reads MRPT's
// archive (mrpt_rawlog_reader.h); every other format goes to ReadTrace.
// ("auto" decides rawlogs by extension: the archive is binary, and the
// content-based detection of the text formats would reject it.)
#include <memory>
#include <string>

#include "traces/mrpt/mrpt_rawlog_reader.h"
#include "traces/trace_reader.h"

namespace rc {

// The format names this reader accepts: ReadTrace's plus "rawlog".
std::string TraceFormatNamesWithRawlog();  // "auto, cmu, rowild, carmen or rawlog"

SensorTrace ReadTraceWithRawlog(const std::string& path, const TraceReadOptions& options,
                                const RawlogReadOptions& rawlog = {}, TraceReadStats* stats = nullptr);

// OpenTraceStream plus rawlogs. MRPT deserializes a rawlog whole, so a
// rawlog is read into memory and served from there; the text formats stream.
std::unique_ptr<ScanSource> OpenTraceStreamWithRawlog(const std::string& path, const TraceReadOptions& options,
                                                      const RawlogReadOptions& rawlog = {},
                                                      TraceReadStats* stats = nullptr);

}  // namespace rc
