#pragma once
// Reader for RoWild DeliBot's laser log (shared/data/wean/rowild_log1.txt):
// one line per laser record, 183 numbers:
//   x y theta r1 .. r180        (cm, cm, rad, then ranges in cm)
// It is the CMU robotdata format's L records with the laser pose and the
// timestamp dropped (and the pose rounded to 3 decimals), so the geometry is
// the same CMU laser (CmuLaserGeometry()).
//
// Time: the format has none, and we do not invent one. Every scan gets
// time_s = 0, which LaserTimeOrder accepts (equal times are in order). The
// odometry motion model uses pose differences only, so MCL is unaffected;
// anything that needs real time (timeline plots against seconds) must use the
// CMU log instead, or plot against the record index.
#include <fstream>
#include <string>

#include "common/text_fields.h"
#include "traces/laser_record_stream.h"
#include "traces/sensor_trace.h"
#include "traces/trace_read_stats.h"

namespace rc {

// Throws InputError (file, 1-based line, field) on a line with other than 183
// fields, a non-numeric, NaN or inf value, a negative range, or a file with no
// records. Blank lines are skipped; nothing is repaired.
SensorTrace ReadRowildLog(const std::string& path, TraceReadStats* stats = nullptr);

// The same reader, one record at a time.
class RowildLogStream final : public LaserRecordStream {
 public:
  // Throws InputError if the file cannot be opened.
  explicit RowildLogStream(const std::string& path);
  bool Next(LaserScan& scan) override;
  const LaserGeometry& geometry() const override { return geometry_; }
  const TraceReadStats& stats() const override { return stats_; }

 private:
  std::ifstream in_;
  LineReader reader_;
  LaserGeometry geometry_;
  TraceReadStats stats_;
};

}  // namespace rc
