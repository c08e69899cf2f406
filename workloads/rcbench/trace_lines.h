#pragma once
// The lines a subcommand prints about a trace it read: what it holds, where
// its laser mount came from, and the warnings a valid but glitchy log earns
// (a counted warning, never a silent repair and never an exit).
#include <ostream>
#include <string>

#include "traces/scan_source.h"
#include "traces/trace_read_stats.h"

namespace rc {

// `mount_given`: the mount came from --laser-offset.
void PrintTraceLines(std::ostream& out, std::ostream& warnings, const ScanSource& trace, const TraceReadStats& stats,
                     bool mount_given);

}  // namespace rc
