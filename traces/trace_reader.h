#pragma once
// One entry point for every supported trace format, so the command line and
// the workloads need not know which reader a file needs.
#include <memory>
#include <optional>
#include <string>

#include "traces/carmen_log_reader.h"
#include "traces/cmu_log_reader.h"
#include "traces/scan_source.h"
#include "traces/sensor_trace.h"
#include "traces/trace_read_stats.h"

namespace rc {

struct TraceReadOptions {
  // "auto", "cmu", "rowild" or "carmen". "auto" decides by content, see
  // DetectTraceFormat.
  std::string format = "auto";
  // 0: take the beam count from the format. Otherwise a trace with another
  // beam count is an InputError (e.g. a 361-beam CARMEN log given to a run
  // configured for the 180-beam CMU laser).
  int expected_beam_count = 0;
  // Set: the laser's forward offset (m) for every format, instead of the
  // mount the file's laser poses state (CMU, CARMEN) or the Wean robot's
  // 0.25 m (RoWild, whose lines carry no laser pose). Overrides cmu and
  // carmen's own setting.
  std::optional<double> laser_offset_forward_m;
  CmuLogOptions cmu;
  CarmenLogOptions carmen;
};

// Returns "cmu", "rowild" or "carmen" from the first line that is neither
// blank nor a '#' comment (a '#' line itself means CARMEN, the only format
// with comments): first field "O" or "L" -> cmu (robotdata*.log); a message
// name from CARMEN's logger header (PARAM, ODOM, FLASER, ROBOTLASER1, SYNC,
// ...) -> carmen (.clf, or .log from CARMEN's logger);
// 183 numbers -> rowild (.txt). Extensions are ambiguous (.log is both CMU
// and CARMEN), so content decides. Throws InputError if nothing matches.
std::string DetectTraceFormat(const std::string& path);

// Throws UsageError for an unknown format name, InputError for bad input.
SensorTrace ReadTrace(const std::string& path, const TraceReadOptions& options, TraceReadStats* stats = nullptr);

// The same trace as a stream (scan_source.h): the file is read once here to
// validate it (every InputError ReadTrace would raise is raised now) and
// then served record by record, so a run's memory does not grow with the
// trace's length. *stats describes the whole file.
std::unique_ptr<ScanSource> OpenTraceStream(const std::string& path, const TraceReadOptions& options,
                                            TraceReadStats* stats = nullptr);

// Applies options.laser_offset_forward_m to a trace read some other way (an
// MRPT rawlog). Throws UsageError for an offset outside [0, 10] m.
void ApplyLaserOffset(const TraceReadOptions& options, LaserGeometry& geometry);

}  // namespace rc
