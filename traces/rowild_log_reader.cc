#include "traces/rowild_log_reader.h"

#include <fstream>

#include "common/text_fields.h"
#include "traces/cmu_laser_geometry.h"
#include "traces/record_fields.h"

namespace rc {
namespace {

constexpr std::size_t kBeams = 180;
constexpr std::size_t kPoseFields = 3;
constexpr std::size_t kRecordFields = kPoseFields + kBeams;
const char* const kLayout = "x y theta r1..r180";

std::string FieldName(std::size_t i) {
  static const char* const kPoseNames[] = {"x", "y", "theta"};
  return i < kPoseFields ? kPoseNames[i] : RangeFieldName(i - kPoseFields);
}

}  // namespace

RowildLogStream::RowildLogStream(const std::string& path)
    : in_(path), reader_(in_, path), geometry_(CmuLaserGeometry()) {
  if (!in_) throw InputError(path, 0, "", "cannot open trace file");
}

bool RowildLogStream::Next(LaserScan& scan) {
  std::string line;
  while (reader_.Next(line)) {
    const auto fields = SplitFields(line);
    if (fields.empty()) continue;
    RequireFieldCount(reader_, fields.size(), kRecordFields, FieldName, kLayout);
    scan.source_line = reader_.line_number();
    scan.time_s = 0.0;  // the format has no timestamps (see header)
    scan.odometry.x = CentimetresToMetres(reader_.ParseDouble(fields[0], "x"));
    scan.odometry.y = CentimetresToMetres(reader_.ParseDouble(fields[1], "y"));
    scan.odometry.theta = reader_.ParseDouble(fields[2], "theta");
    scan.ranges_m.resize(kBeams);
    for (std::size_t b = 0; b < kBeams; ++b) scan.ranges_m[b] = ParseRange(reader_, fields[kPoseFields + b], b, 100.0);
    ++stats_.laser_records;
    return true;
  }
  return false;
}

SensorTrace ReadRowildLog(const std::string& path, TraceReadStats* stats) {
  RowildLogStream stream(path);
  SensorTrace trace;
  trace.source_path = path;
  trace.format = "rowild";
  trace.geometry = stream.geometry();
  LaserScan scan;
  while (stream.Next(scan)) trace.scans.push_back(std::move(scan));
  RequireLaserRecords(trace, "laser records");
  if (stats) *stats = stream.stats();
  return trace;
}

}  // namespace rc
