#pragma once
// Reader for the CMU robot-localization logs (robotdata1..4.log, see
// shared/data/wean/instruct.txt). One record per line, cm and rad:
//   O x y theta ts                              odometry
//   L x y theta xl yl thetal r1 .. r180 ts      laser, with the interpolated
//                                               robot pose and laser pose
// Each L record becomes a LaserScan: odometry = the robot pose (x y theta),
// time = ts, ranges converted to metres, geometry = CmuLaserGeometry().
// O records are validated and counted but not returned: the L pose is
// already the odometry interpolated at the scan time, which is all the
// motion model needs.
#include <fstream>
#include <optional>
#include <string>

#include "common/text_fields.h"
#include "traces/laser_mount.h"
#include "traces/laser_record_stream.h"
#include "traces/record_fields.h"
#include "traces/sensor_trace.h"
#include "traces/trace_read_stats.h"

namespace rc {

struct CmuLogOptions {
  // Unset: the mount is measured from the log's own laser poses (xl yl
  // thetal minus x y theta, laser_mount.h): taken from the first L record,
  // and every L record must agree with it within mount_tolerance, so a log of
  // a robot with another mount is read as it is. The Wean logs measure
  // 0.25 m (instruct.txt: "approximately 25 cm").
  // Set (--laser-offset): the laser's forward offset (m); the logged laser
  // pose is then validated as numbers but not used.
  std::optional<double> laser_offset_forward_m;
  LaserMountTolerance mount_tolerance;
};

// Throws InputError (file, 1-based line, field) on anything malformed: an
// unknown record type, a missing or extra field, a non-numeric, NaN or inf
// value, a negative range, a laser record more than a clock glitch earlier
// than the one before (record_fields.h), a laser pose that disagrees with
// the first record's mount or is off the heading axis, or a log without L
// records. Nothing is repaired.
SensorTrace ReadCmuLog(const std::string& path, const CmuLogOptions& options = {}, TraceReadStats* stats = nullptr);

// The same reader, one L record at a time.
class CmuLogStream final : public LaserRecordStream {
 public:
  // Throws InputError if the file cannot be opened.
  CmuLogStream(const std::string& path, const CmuLogOptions& options);
  bool Next(LaserScan& scan) override;
  const LaserGeometry& geometry() const override { return geometry_; }
  const TraceReadStats& stats() const override { return stats_; }

 private:
  std::ifstream in_;
  LineReader reader_;
  CmuLogOptions options_;
  LaserGeometry geometry_;
  std::string mount_source_;  // where the mount came from, once known
  LaserTimeOrder time_order_;
  TraceReadStats stats_;
};

}  // namespace rc
