#include "traces/carmen_log_reader.h"

#include <cctype>
#include <fstream>
#include <map>
#include <optional>
#include <vector>

#include "common/text_fields.h"
#include "traces/record_fields.h"

namespace rc {
namespace {

constexpr long kMaxBeams = 100000;  // far beyond any 2D scanner
constexpr double kDegToRad = kPi / 180.0;
const char* const kFlaserLayout =
    "FLASER num_readings r1..rn x y theta odom_x odom_y odom_theta timestamp hostname "
    "logger_timestamp";
const char* const kRobotLaserLayout =
    "ROBOTLASER1 laser_type start_angle field_of_view angular_resolution maximum_range accuracy "
    "remission_mode num_readings r1..rn num_remissions m1..mk laser_x laser_y laser_theta "
    "robot_x robot_y robot_theta tv rv forward_safety_dist side_safety_dist turn_axis timestamp "
    "hostname logger_timestamp";
const char* const kOdomLayout = "ODOM x y theta tv rv accel timestamp hostname logger_timestamp";

using Fields = std::vector<std::string_view>;

std::string NameOrPosition(const char* const* names, std::size_t count, std::size_t k, std::size_t absolute_index) {
  return k < count ? names[k] : "field " + std::to_string(absolute_index + 1);
}

// One parsed laser message, before it is checked against the earlier ones.
struct LaserRecord {
  std::string kind;
  LaserGeometry geometry;  // ROBOTLASER1: as logged; FLASER: beam count only
  Pose2 laser_pose;
  LaserScan scan;
};

Pose2 ParsePose(const LineReader& reader, const Fields& f, std::size_t first, const char* x, const char* y,
                const char* theta) {
  return Pose2{reader.ParseDouble(f[first], x), reader.ParseDouble(f[first + 1], y),
               reader.ParseDouble(f[first + 2], theta)};
}

// "timestamp hostname logger_timestamp" at f[first..]; returns the IPC time.
double ParseTrailer(const LineReader& reader, const Fields& f, std::size_t first) {
  const double ipc_time = reader.ParseDouble(f[first], "timestamp");
  reader.ParseDouble(f[first + 2], "logger_timestamp");  // f[first + 1] is a host name
  return ipc_time;
}

LaserRecord ParseFlaser(const LineReader& reader, const Fields& f) {
  static const char* const kTail[] = {"x",          "y",         "theta",    "odom_x",          "odom_y",
                                      "odom_theta", "timestamp", "hostname", "logger_timestamp"};
  if (f.size() < 2) reader.Fail("num_readings", "missing (" + std::string(kFlaserLayout) + ")");
  const std::size_t n = static_cast<std::size_t>(reader.ParseInt(f[1], "num_readings", 1, kMaxBeams));
  auto name_of = [n](std::size_t i) -> std::string {
    if (i == 0) return "message";
    if (i == 1) return "num_readings";
    if (i < 2 + n) return RangeFieldName(i - 2);
    return NameOrPosition(kTail, 9, i - 2 - n, i);
  };
  // A num_readings that disagrees with the ranges shifts the 9 trailing
  // fields, so a field-by-field check would blame one of them
  // (logger_timestamp). A line that still ends in a whole trailer (its host
  // name, second to last, is not a number) holds f.size() - 11 ranges: the
  // count is what is wrong. A line cut off mid-record has a number there and
  // is reported below by its first missing field.
  if (f.size() != n + 11 && f.size() >= 11 && !LooksNumeric(f[f.size() - 2]))
    reader.Fail("num_readings", "says " + std::to_string(n) + " readings, but the line holds " +
                                    std::to_string(f.size() - 11) + " values before its 9 trailing fields (" +
                                    kFlaserLayout + ")");
  RequireFieldCount(reader, f.size(), n + 11, name_of, kFlaserLayout);
  LaserRecord record;
  record.kind = "FLASER";
  record.geometry.beam_count = static_cast<int>(n);
  record.scan.ranges_m.resize(n);
  for (std::size_t b = 0; b < n; ++b) record.scan.ranges_m[b] = ParseRange(reader, f[2 + b], b, 1.0);
  record.laser_pose = ParsePose(reader, f, 2 + n, "x", "y", "theta");
  record.scan.odometry = ParsePose(reader, f, 5 + n, "odom_x", "odom_y", "odom_theta");
  record.scan.time_s = ParseTrailer(reader, f, 8 + n);
  return record;
}

// A count field's value: a plain non-negative integer up to kMaxBeams.
std::optional<std::size_t> CountIn(std::string_view token) {
  if (token.empty() || token.size() > 6) return std::nullopt;
  std::size_t value = 0;
  for (char c : token) {
    if (!std::isdigit(static_cast<unsigned char>(c))) return std::nullopt;
    value = 10 * value + static_cast<std::size_t>(c - '0');
  }
  if (value > static_cast<std::size_t>(kMaxBeams)) return std::nullopt;
  return value;
}

// ROBOTLASER1 carries two counts, and one that disagrees with the values
// present shifts every field after it, so the field-by-field checks would
// blame num_remissions, a remission or a trailing field. A line that still
// ends in a whole 14-field trailer (its host name, second to last, is not a
// number) holds its ranges, num_remissions and remissions in the
// f.size() - 23 fields after num_readings; this names the count that does
// not fit them:
// - the field after the n stated ranges is a count: it is taken as
//   num_remissions (CARMEN writes ranges and remissions with decimals), so
//   num_remissions is wrong;
// - otherwise num_readings is, and where some other reading count fits
//   (a count after that many ranges, then exactly that many remissions),
//   the message gives it.
// A line cut off mid-record has a number second to last and is reported by
// its first missing field.
void CheckRobotLaserCounts(const LineReader& reader, const Fields& f, std::size_t n) {
  if (f.size() < 24 || LooksNumeric(f[f.size() - 2])) return;
  const std::size_t values = f.size() - 23;
  auto fits = [&](std::size_t readings) {
    if (readings + 1 > values) return false;
    const std::optional<std::size_t> m = CountIn(f[9 + readings]);
    return m && readings + 1 + *m == values;
  };
  if (fits(n)) return;
  const std::string trailer = " before its 14 trailing fields (" + std::string(kRobotLaserLayout) + ")";
  if (n + 1 <= values) {
    if (const std::optional<std::size_t> m = CountIn(f[9 + n]))
      reader.Fail("num_remissions", "says " + std::to_string(*m) + " remissions, but the line holds " +
                                        std::to_string(values - n - 1) + " values after it" + trailer);
  }
  auto distance = [n](std::size_t k) { return k > n ? k - n : n - k; };
  std::optional<std::size_t> held;  // the fitting reading count nearest n
  for (std::size_t k = 1; k + 1 <= values; ++k)
    if (fits(k) && (!held || distance(k) < distance(*held))) held = k;
  const std::string says = "says " + std::to_string(n) + " readings, but ";
  if (held)
    reader.Fail("num_readings", says + "the line holds " + std::to_string(*held) + " (then num_remissions " +
                                    std::string(f[9 + *held]) + " and its remissions)" + trailer);
  if (n + 1 > values)
    reader.Fail("num_readings", says + "the line holds only " + std::to_string(values) +
                                    " values for them, num_remissions and the remissions" + trailer);
  if (LooksNumeric(f[9 + n]))
    reader.Fail("num_readings", says + "field " + std::to_string(10 + n) + " ('" + std::string(f[9 + n]) +
                                    "'), where num_remissions should follow them, is not a count, and no other "
                                    "reading count fits the line" +
                                    trailer);
  // A word there is a corrupt num_remissions, which parsing it reports.
}

LaserRecord ParseRobotLaser(const LineReader& reader, const Fields& f) {
  static const char* const kHead[] = {"message",       "laser_type",         "start_angle",
                                      "field_of_view", "angular_resolution", "maximum_range",
                                      "accuracy",      "remission_mode",     "num_readings"};
  static const char* const kTail[] = {"laser_x",
                                      "laser_y",
                                      "laser_theta",
                                      "robot_x",
                                      "robot_y",
                                      "robot_theta",
                                      "tv",
                                      "rv",
                                      "forward_safety_dist",
                                      "side_safety_dist",
                                      "turn_axis",
                                      "timestamp",
                                      "hostname",
                                      "logger_timestamp"};
  std::size_t n = 0, m = 0;
  bool know_m = false;
  auto name_of = [&](std::size_t i) -> std::string {
    if (i < 9) return kHead[i];
    if (i < 9 + n) return RangeFieldName(i - 9);
    if (i == 9 + n) return "num_remissions";
    if (!know_m) return "field " + std::to_string(i + 1);
    if (i < 10 + n + m) return "remission " + std::to_string(i - 9 - n);
    return NameOrPosition(kTail, 14, i - 10 - n - m, i);
  };
  if (f.size() < 9) RequireFieldCount(reader, f.size(), 9, name_of, kRobotLaserLayout);
  LaserRecord record;
  record.kind = "ROBOTLASER1";
  reader.ParseInt(f[1], "laser_type", 0, 1000);
  record.geometry.angle_min_rad = reader.ParseDouble(f[2], "start_angle");
  reader.ParseDouble(f[3], "field_of_view");
  record.geometry.angle_increment_rad = reader.ParseDouble(f[4], "angular_resolution");
  if (!(record.geometry.angle_increment_rad > 0.0)) reader.Fail("angular_resolution", "must be positive (rad)");
  record.geometry.max_range_m = reader.ParseDouble(f[5], "maximum_range");
  if (!(record.geometry.max_range_m > 0.0)) reader.Fail("maximum_range", "must be positive (m)");
  reader.ParseDouble(f[6], "accuracy");
  reader.ParseInt(f[7], "remission_mode", 0, 1000);
  n = static_cast<std::size_t>(reader.ParseInt(f[8], "num_readings", 1, kMaxBeams));
  CheckRobotLaserCounts(reader, f, n);
  if (f.size() < 10 + n) RequireFieldCount(reader, f.size(), 10 + n, name_of, kRobotLaserLayout);
  m = static_cast<std::size_t>(reader.ParseInt(f[9 + n], "num_remissions", 0, kMaxBeams));
  know_m = true;
  RequireFieldCount(reader, f.size(), n + m + 24, name_of, kRobotLaserLayout);

  record.geometry.beam_count = static_cast<int>(n);
  record.scan.ranges_m.resize(n);
  for (std::size_t b = 0; b < n; ++b) record.scan.ranges_m[b] = ParseRange(reader, f[9 + b], b, 1.0);
  for (std::size_t j = 0; j < m; ++j) reader.ParseDouble(f[10 + n + j], "remission " + std::to_string(j + 1));
  const std::size_t tail = 10 + n + m;
  record.laser_pose = ParsePose(reader, f, tail, "laser_x", "laser_y", "laser_theta");
  record.scan.odometry = ParsePose(reader, f, tail + 3, "robot_x", "robot_y", "robot_theta");
  for (std::size_t k = 6; k < 11; ++k) reader.ParseDouble(f[tail + k], kTail[k]);
  record.scan.time_s = ParseTrailer(reader, f, tail + 11);
  return record;
}

void ParseOdom(const LineReader& reader, const Fields& f) {
  static const char* const kNames[] = {"message", "x",     "y",         "theta",    "tv",
                                       "rv",      "accel", "timestamp", "hostname", "logger_timestamp"};
  RequireFieldCount(
      reader, f.size(), 10, [](std::size_t i) { return NameOrPosition(kNames, 10, i, i); }, kOdomLayout);
  for (std::size_t i = 1; i < 7; ++i) reader.ParseDouble(f[i], kNames[i]);
  ParseTrailer(reader, f, 7);
}

// CARMEN message names are upper-case words (ODOM, SYNC, NMEAGGA, ...);
// anything else, such as a CMU "O"/"L" record or a number, means the file is
// not a CARMEN log, which must not pass as a log of unknown messages.
bool IsMessageName(std::string_view token) {
  if (token.size() < 2 || !std::isupper(static_cast<unsigned char>(token[0]))) return false;
  for (char c : token)
    if (!std::isupper(static_cast<unsigned char>(c)) && !std::isdigit(static_cast<unsigned char>(c)) && c != '_')
      return false;
  return true;
}

// Carries what the first laser record fixed (kind, geometry, mount) and
// checks every later one against it.
class LaserRecordChecker {
 public:
  LaserRecordChecker(const CarmenLogOptions& options, TraceReadStats& stats) : options_(options), stats_(stats) {}

  // PARAM values that set FLASER geometry; they must come before it is fixed.
  void SetParam(const LineReader& reader, const std::string& name, std::string_view value) {
    if (name != "robot_front_laser_max" && name != "laser_front_laser_resolution") return;
    const double v = reader.ParseDouble(value, name);
    if (!(v > 0.0)) reader.Fail(name, "must be positive");
    // ROBOTLASER1 states its own geometry; these PARAMs only shape FLASER's.
    const bool fixed = kind_ == "FLASER";
    if (fixed && params_.count(name) && params_[name] != v)
      reader.Fail(name, "changes after the first laser record (line " + std::to_string(first_line_) +
                            "); one geometry per trace");
    if (fixed && !params_.count(name))
      reader.Fail(name, "comes after the first laser record (line " + std::to_string(first_line_) +
                            "), whose geometry is already fixed");
    params_[name] = v;
  }

  // Checks the record against the first one and returns its scan.
  LaserScan Accept(const LineReader& reader, LaserRecord record) {
    if (kind_.empty())
      Fix(reader, record);
    else
      CheckSameGeometry(reader, record);
    const LaserMountOffset mount = MeasureMountOffset(record.scan.odometry, record.laser_pose);
    stats_.laser_mount.Add(mount);
    if (!options_.laser_offset_forward_m) {
      const bool flaser = kind_ == "FLASER";
      CheckMountOffset(reader, mount, geometry_.offset_forward_m, options_.mount_tolerance,
                       flaser ? "x/y" : "laser_x/laser_y", flaser ? "theta" : "laser_theta",
                       "the mount of the first laser record, line " + std::to_string(first_line_));
    }
    time_order_.Check(reader, record.scan.time_s, "timestamp");
    record.scan.source_line = reader.line_number();
    return std::move(record.scan);
  }

  const LaserGeometry& geometry() const { return geometry_; }

  const TimeGlitchStats& time_glitches() const { return time_order_.glitches(); }

 private:
  void Fix(const LineReader& reader, const LaserRecord& record) {
    kind_ = record.kind;
    first_line_ = reader.line_number();
    LaserGeometry& g = geometry_;
    g = record.geometry;
    if (kind_ == "FLASER") {
      const int n = g.beam_count;
      auto resolution = params_.find("laser_front_laser_resolution");
      if (resolution != params_.end()) {
        g.angle_increment_rad = resolution->second * kDegToRad;
      } else {
        if (n < 2) reader.Fail("num_readings", "a 1-beam FLASER has no defined angular step");
        g.angle_increment_rad = kPi / (n - n % 2);
      }
      g.angle_min_rad = -kPi / 2.0;
      auto max_range = params_.find("robot_front_laser_max");
      g.max_range_m = max_range != params_.end() ? max_range->second : options_.default_max_range_m;
    }
    g.offset_forward_m = options_.laser_offset_forward_m
                             ? *options_.laser_offset_forward_m
                             : RoundMountOffset(MeasureMountOffset(record.scan.odometry, record.laser_pose).forward_m);
  }

  void CheckSameGeometry(const LineReader& reader, const LaserRecord& record) const {
    const std::string since = " (line " + std::to_string(first_line_) + ")";
    if (record.kind != kind_)
      reader.Fail("message", "a " + record.kind + " record after " + kind_ + " records" + since +
                                 ": both describe the front laser; a log must use one");
    const LaserGeometry& g = geometry_;
    if (record.geometry.beam_count != g.beam_count)
      reader.Fail("num_readings", std::to_string(record.geometry.beam_count) + " beams, but the first laser record" +
                                      since + " has " + std::to_string(g.beam_count));
    if (kind_ != "ROBOTLASER1") return;
    if (record.geometry.angle_min_rad != g.angle_min_rad)
      reader.Fail("start_angle", "differs from the first laser record" + since);
    if (record.geometry.angle_increment_rad != g.angle_increment_rad)
      reader.Fail("angular_resolution", "differs from the first laser record" + since);
    if (record.geometry.max_range_m != g.max_range_m)
      reader.Fail("maximum_range", "differs from the first laser record" + since);
  }

  const CarmenLogOptions& options_;
  TraceReadStats& stats_;
  LaserGeometry geometry_;
  std::string kind_;  // empty until the first laser record
  long first_line_ = 0;
  std::map<std::string, double> params_;
  LaserTimeOrder time_order_;
};

}  // namespace

struct CarmenLogStream::State {
  State(const CarmenLogOptions& o, TraceReadStats& stats) : options(o), checker(options, stats) {}
  CarmenLogOptions options;
  LaserRecordChecker checker;
};

CarmenLogStream::CarmenLogStream(const std::string& path, const CarmenLogOptions& options)
    : in_(path), reader_(in_, path), state_(std::make_unique<State>(options, stats_)) {
  if (!in_) throw InputError(path, 0, "", "cannot open trace file");
}

CarmenLogStream::~CarmenLogStream() = default;

const LaserGeometry& CarmenLogStream::geometry() const { return state_->checker.geometry(); }

bool CarmenLogStream::Next(LaserScan& scan) {
  LaserRecordChecker& checker = state_->checker;
  std::string line;
  while (reader_.Next(line)) {
    const Fields f = SplitFields(line);
    if (f.empty() || f[0][0] == '#') continue;
    if (f[0] == "FLASER" || f[0] == "ROBOTLASER1") {
      scan = checker.Accept(reader_, f[0] == "FLASER" ? ParseFlaser(reader_, f) : ParseRobotLaser(reader_, f));
      ++stats_.laser_records;
      stats_.time_glitches = checker.time_glitches();
      return true;
    }
    if (f[0] == "ODOM") {
      ParseOdom(reader_, f);
      ++stats_.odometry_records;
    } else if (f[0] == "PARAM") {
      if (f.size() < 3) reader_.Fail("value", "expected 'PARAM name value'");
      checker.SetParam(reader_, std::string(f[1]), f[2]);
      ++stats_.skipped_records;
    } else if (IsMessageName(f[0])) {
      ++stats_.skipped_records;  // another sensor's message
    } else {
      reader_.Fail("message", "'" + std::string(f[0]) + "' is not a CARMEN message name");
    }
  }
  return false;
}

SensorTrace ReadCarmenLog(const std::string& path, const CarmenLogOptions& options, TraceReadStats* stats) {
  CarmenLogStream stream(path, options);
  SensorTrace trace;
  trace.source_path = path;
  trace.format = "carmen";
  LaserScan scan;
  while (stream.Next(scan)) trace.scans.push_back(std::move(scan));
  trace.geometry = stream.geometry();
  RequireLaserRecords(trace, "FLASER or ROBOTLASER1 records");
  if (stats) *stats = stream.stats();
  return trace;
}

}  // namespace rc
