#include "traces/cmu_log_reader.h"

#include <fstream>

#include "common/text_fields.h"
#include "traces/cmu_laser_geometry.h"
#include "traces/record_fields.h"

namespace rc {
namespace {

constexpr std::size_t kBeams = 180;
// L x y theta xl yl thetal r1..r180 ts
constexpr std::size_t kFirstRangeField = 7;
constexpr std::size_t kLaserFields = kFirstRangeField + kBeams + 1;
constexpr std::size_t kOdometryFields = 5;  // O x y theta ts
const char* const kLaserLayout = "L x y theta xl yl thetal r1..r180 ts";
const char* const kOdometryLayout = "O x y theta ts";

std::string LaserFieldName(std::size_t i) {
  static const char* const kPoseNames[] = {"record type", "x", "y", "theta", "xl", "yl", "thetal"};
  if (i < kFirstRangeField) return kPoseNames[i];
  if (i < kFirstRangeField + kBeams) return RangeFieldName(i - kFirstRangeField);
  return "ts";
}

std::string OdometryFieldName(std::size_t i) {
  static const char* const kNames[] = {"record type", "x", "y", "theta", "ts"};
  return i < kOdometryFields ? kNames[i] : "field " + std::to_string(i + 1);
}

// Robot or laser pose from three fields in cm, cm, rad.
Pose2 ParsePoseCm(const LineReader& reader, const std::vector<std::string_view>& fields, std::size_t first,
                  const char* x_name, const char* y_name, const char* theta_name) {
  Pose2 pose;
  pose.x = CentimetresToMetres(reader.ParseDouble(fields[first], x_name));
  pose.y = CentimetresToMetres(reader.ParseDouble(fields[first + 1], y_name));
  pose.theta = reader.ParseDouble(fields[first + 2], theta_name);
  return pose;
}

}  // namespace

CmuLogStream::CmuLogStream(const std::string& path, const CmuLogOptions& options)
    : in_(path), reader_(in_, path), options_(options), geometry_(CmuLaserGeometry()) {
  if (!in_) throw InputError(path, 0, "", "cannot open trace file");
  if (options_.laser_offset_forward_m) geometry_.offset_forward_m = *options_.laser_offset_forward_m;
}

bool CmuLogStream::Next(LaserScan& scan) {
  std::string line;
  while (reader_.Next(line)) {
    const auto fields = SplitFields(line);
    if (fields.empty()) continue;  // a blank line carries no record
    if (fields[0] == "O") {
      RequireFieldCount(reader_, fields.size(), kOdometryFields, OdometryFieldName, kOdometryLayout);
      ParsePoseCm(reader_, fields, 1, "x", "y", "theta");
      reader_.ParseDouble(fields[4], "ts");
      ++stats_.odometry_records;
      continue;
    }
    if (fields[0] != "L") reader_.Fail("record type", "'" + std::string(fields[0]) + "' is neither O nor L");

    RequireFieldCount(reader_, fields.size(), kLaserFields, LaserFieldName, kLaserLayout);
    scan.source_line = reader_.line_number();
    scan.odometry = ParsePoseCm(reader_, fields, 1, "x", "y", "theta");
    const Pose2 laser = ParsePoseCm(reader_, fields, 4, "xl", "yl", "thetal");
    const LaserMountOffset mount = MeasureMountOffset(scan.odometry, laser);
    if (!options_.laser_offset_forward_m) {
      if (mount_source_.empty()) {
        geometry_.offset_forward_m = RoundMountOffset(mount.forward_m);
        mount_source_ = "the mount of the first L record, line " + std::to_string(reader_.line_number());
      }
      CheckMountOffset(reader_, mount, geometry_.offset_forward_m, options_.mount_tolerance, "xl/yl", "thetal",
                       mount_source_);
    }
    stats_.laser_mount.Add(mount);
    scan.ranges_m.resize(kBeams);
    for (std::size_t b = 0; b < kBeams; ++b)
      scan.ranges_m[b] = ParseRange(reader_, fields[kFirstRangeField + b], b, 100.0);
    scan.time_s = reader_.ParseDouble(fields[kLaserFields - 1], "ts");
    time_order_.Check(reader_, scan.time_s, "ts");
    stats_.time_glitches = time_order_.glitches();
    ++stats_.laser_records;
    return true;
  }
  return false;
}

SensorTrace ReadCmuLog(const std::string& path, const CmuLogOptions& options, TraceReadStats* stats) {
  CmuLogStream stream(path, options);
  SensorTrace trace;
  trace.source_path = path;
  trace.format = "cmu";
  LaserScan scan;
  while (stream.Next(scan)) trace.scans.push_back(std::move(scan));
  trace.geometry = stream.geometry();
  RequireLaserRecords(trace, "L records");
  if (stats) *stats = stream.stats();
  return trace;
}

}  // namespace rc
