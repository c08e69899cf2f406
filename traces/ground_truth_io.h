#pragma once
// Ground-truth poses for a trace: a text file with one line per laser record,
//   t x y theta            (s, m, m, rad)
// '#' lines are comments (the writer puts the column names in one). The
// simulator writes these beside the traces it makes; accuracy metrics read
// them and pair line k with laser record k.
#include <string>
#include <vector>

#include "common/angles.h"
#include "traces/scan_source.h"
#include "traces/sensor_trace.h"

namespace rc {

struct GroundTruthPose {
  double time_s = 0.0;
  Pose2 pose;            // m, m, rad, in the map frame
  long source_line = 0;  // 1-based line in the file (0 if not read from one)
};

struct GroundTruth {
  std::string source_path;
  std::vector<GroundTruthPose> poses;
};

// Throws InputError (file, 1-based line, field "t" / "x" / "y" / "theta") on a
// line without exactly 4 fields, a non-numeric, NaN or inf value, or a file
// with no poses. Blank and '#' lines are skipped.
GroundTruth ReadGroundTruth(const std::string& path);

// Writes through AtomicFile with %.17g (doubles round-trip exactly, which
// matters for absolute CARMEN times near 1e9 s). Throws std::invalid_argument
// on a non-finite value (a bug in the caller, not an input error), and
// std::runtime_error if the file cannot be written.
void WriteGroundTruth(const std::string& path, const std::vector<GroundTruthPose>& poses);

// Ground truth pairs with a trace by position, so it must have exactly one
// pose per laser record, and pose k's time must equal scan k's time (within
// 1 us; RoWild traces have time 0 everywhere, so their ground truth must too).
// Throws InputError naming the ground-truth file otherwise.
void CheckGroundTruthMatches(const SensorTrace& trace, const GroundTruth& truth);
// The same check over a stream; leaves it rewound to its first record.
void CheckGroundTruthMatches(ScanSource& scans, const GroundTruth& truth);

}  // namespace rc
