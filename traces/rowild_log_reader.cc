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

SensorTrace ReadRowildLog(const std::string& path, TraceReadStats* stats) {
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "", "cannot open trace file");
  LineReader reader(in, path);
  SensorTrace trace;
  trace.source_path = path;
  trace.format = "rowild";
  trace.geometry = CmuLaserGeometry();

  std::string line;
  while (reader.Next(line)) {
    const auto fields = SplitFields(line);
    if (fields.empty()) continue;
    RequireFieldCount(reader, fields.size(), kRecordFields, FieldName, kLayout);
    LaserScan scan;
    scan.source_line = reader.line_number();
    scan.time_s = 0.0;  // the format has no timestamps (see header)
    scan.odometry.x = CentimetresToMetres(reader.ParseDouble(fields[0], "x"));
    scan.odometry.y = CentimetresToMetres(reader.ParseDouble(fields[1], "y"));
    scan.odometry.theta = reader.ParseDouble(fields[2], "theta");
    scan.ranges_m.resize(kBeams);
    for (std::size_t b = 0; b < kBeams; ++b)
      scan.ranges_m[b] = ParseRange(reader, fields[kPoseFields + b], b, 100.0);
    trace.scans.push_back(std::move(scan));
  }
  RequireLaserRecords(trace, "laser records");
  TraceReadStats local_stats;
  local_stats.laser_records = static_cast<long>(trace.scans.size());
  if (stats) *stats = local_stats;
  return trace;
}

}  // namespace rc
