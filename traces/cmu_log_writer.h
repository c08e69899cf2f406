#pragma once
// Writes a SensorTrace as a CMU robotdata log (the format ReadCmuLog reads),
// so simulated traces can be fed to tools that only know that format,
// RoWild's DeliBot included after its own conversion.
//   L x y theta xl yl thetal r1..r180 ts    (cm, rad, s)
// The laser pose is the robot pose moved geometry.offset_forward_m along the
// heading. Poses and times are printed with 6 decimals as in the original
// logs (1e-8 m, 1e-6 rad, 1 us); each range with the fewest decimals that
// read back to the same float, so a written-then-read trace has identical
// ranges and real logs are written back as whole cm.
// A no-return reading (>= geometry.max_range_m) of a trace whose max range is
// below 81.83 m is written as the SICK code 8183 cm, so ReadCmuLog still reads
// it as no return; readings already >= 81.83 m (the SICK codes of a real log)
// are written as they are.
#include <string>

#include "traces/sensor_trace.h"

namespace rc {

struct CmuLogWriteOptions {
  // Also write "O x y theta ts" before each L record, with the L record's pose
  // and time (the original logs interleave odometry; ReadCmuLog only counts it).
  bool odometry_records = false;
};

// Throws UsageError if the trace's geometry is not the CMU laser's (180 beams,
// 1 deg, from -90 deg) or holds a reading the format cannot carry (a valid
// range >= 81.83 m); std::invalid_argument if a scan has the wrong beam count
// or a NaN, inf or negative value, or times go backwards (caller bugs);
// std::runtime_error if the file cannot be written. Writes via AtomicFile.
void WriteCmuLog(const SensorTrace& trace, const std::string& path, const CmuLogWriteOptions& options = {});

}  // namespace rc
