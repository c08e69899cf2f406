#pragma once
// Writes a SensorTrace as an MRPT .rawlog, in either form, so that our
// simulated traces can be fed to MRPT's own tools and so that tests can
// produce both forms (MRPT ships only an actions/observations example).
//
// Geometry: aperture = increment * (beams - 1), sensor yaw = angle_min +
// aperture / 2, sensor pose (offset_forward_m, 0, 0), maxRange = max_range_m,
// right to left. Readings at or beyond max_range_m are written as invalid
// (MRPT's "no return"). ReadMrptRawlog returns the same trace (ranges exact,
// poses to float precision in the actions form, whose increments MRPT stores
// in single precision).
#include <string>

#include "traces/sensor_trace.h"

namespace rc {

enum class RawlogForm { kActionsObservations, kObservationsOnly };

// Written through a temporary file and renamed, so a failed write leaves no
// partial rawlog. Throws std::runtime_error when the file cannot be written.
void WriteMrptRawlog(const SensorTrace& trace, const std::string& path, RawlogForm form);

}  // namespace rc
