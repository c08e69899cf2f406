#include "traces/cmu_log_reader.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include "support/input_error_expectations.h"
#include "support/temp_dir.h"
#include "support/test_data.h"
#include "traces/cmu_laser_geometry.h"
#include "traces/record_fields.h"

namespace rc {
namespace {

using test::ExpectInputError;
using test::TempDir;

// One well-formed L record, to be broken one field at a time.
struct CmuLaserLine {
  double x_cm = 100.0, y_cm = 200.0, theta = 0.5, ts = 1.0;
  double laser_offset_cm = 25.0;
  double laser_lateral_cm = 0.0;  // left of the heading axis
  double laser_theta_offset = 0.0;
  std::vector<std::string> ranges = std::vector<std::string>(180, "300");

  std::string Text() const {
    char head[256];
    std::snprintf(head, sizeof head, "L %.6f %.6f %.6f %.6f %.6f %.6f", x_cm, y_cm, theta,
                  x_cm + laser_offset_cm * std::cos(theta) - laser_lateral_cm * std::sin(theta),
                  y_cm + laser_offset_cm * std::sin(theta) + laser_lateral_cm * std::cos(theta),
                  theta + laser_theta_offset);
    std::string line = head;
    for (const std::string& r : ranges) line += " " + r;
    char tail[64];
    std::snprintf(tail, sizeof tail, " %.6f\n", ts);
    return line + tail;
  }
};

const std::string kOdometryLine = "O 100.000000 200.000000 0.500000 0.900000\n";

TEST(CmuLogReader, ReadsWellFormedRecordInMetres) {
  TempDir dir;
  CmuLaserLine l;
  l.ranges[0] = "66";
  l.ranges[179] = "8191";
  const std::string path = dir.Write("ok.log", kOdometryLine + l.Text());
  TraceReadStats stats;
  const SensorTrace trace = ReadCmuLog(path, {}, &stats);
  ASSERT_EQ(trace.scans.size(), 1u);
  EXPECT_EQ(trace.format, "cmu");
  const LaserScan& s = trace.scans[0];
  EXPECT_EQ(s.source_line, 2);
  EXPECT_DOUBLE_EQ(s.odometry.x, 1.0);
  EXPECT_DOUBLE_EQ(s.odometry.y, 2.0);
  EXPECT_DOUBLE_EQ(s.odometry.theta, 0.5);
  EXPECT_DOUBLE_EQ(s.time_s, 1.0);
  ASSERT_EQ(s.ranges_m.size(), 180u);
  EXPECT_EQ(s.ranges_m[0], 0.66f);
  EXPECT_EQ(s.ranges_m[1], 3.0f);
  EXPECT_GE(s.ranges_m[179], trace.geometry.max_range_m);  // SICK code: no return
  EXPECT_EQ(stats.laser_records, 1);
  EXPECT_EQ(stats.odometry_records, 1);
}

TEST(CmuLogReader, ZeroRangeIsAValidReading) {
  TempDir dir;
  CmuLaserLine l;
  l.ranges[10] = "0";
  const SensorTrace trace = ReadCmuLog(dir.Write("zero.log", l.Text()));
  EXPECT_EQ(trace.scans[0].ranges_m[10], 0.0f);
}

// A log saved by a Windows editor starts with a UTF-8 byte-order mark.
TEST(CmuLogReader, AByteOrderMarkBeforeTheFirstRecordIsSkipped) {
  TempDir dir;
  const std::string path = dir.Write("bom.log", "\xEF\xBB\xBF" + kOdometryLine + CmuLaserLine().Text());
  TraceReadStats stats;
  const SensorTrace trace = ReadCmuLog(path, {}, &stats);
  ASSERT_EQ(trace.scans.size(), 1u);
  EXPECT_EQ(trace.scans[0].source_line, 2);
  EXPECT_EQ(stats.odometry_records, 1);
}

TEST(CmuLogReader, GeometryIsTheWeanLaser) {
  const LaserGeometry g = CmuLaserGeometry();
  EXPECT_EQ(g.beam_count, 180);
  EXPECT_DOUBLE_EQ(g.BeamAngle(0), -kPi / 2);  // first reading: the right
  EXPECT_DOUBLE_EQ(g.BeamAngle(90), 0.0);      // straight ahead
  EXPECT_NEAR(g.BeamAngle(179), kPi / 2 - kPi / 180, 1e-15);
  EXPECT_DOUBLE_EQ(g.max_range_m, 81.83);
  EXPECT_DOUBLE_EQ(g.offset_forward_m, 0.25);
}

// ---- Bad input: each case names file, line and field. ----

TEST(CmuLogReaderBadInput, NanRange) {
  TempDir dir;
  CmuLaserLine l;
  l.ranges[36] = "nan";
  const std::string path = dir.Write("nan.log", kOdometryLine + l.Text());
  ExpectInputError([&] { ReadCmuLog(path); }, path, 2, "range 37");
}

TEST(CmuLogReaderBadInput, InfRange) {
  TempDir dir;
  CmuLaserLine l;
  l.ranges[0] = "inf";
  const std::string path = dir.Write("inf.log", l.Text());
  ExpectInputError([&] { ReadCmuLog(path); }, path, 1, "range 1");
}

// strtod reads C99 hex floats ("0x1p7" = 128); the format is decimal.
TEST(CmuLogReaderBadInput, HexadecimalRangeOrPose) {
  TempDir dir;
  for (const char* hex : {"0x1p7", "0x10", "0x1p-1"}) {
    CmuLaserLine l;
    l.ranges[13] = hex;
    const std::string path = dir.Write("hex.log", l.Text());
    ExpectInputError([&] { ReadCmuLog(path); }, path, 1, "range 14");
    EXPECT_TRUE(test::ThrowsInputError([&] { ReadCmuLog(path); }, 1, "range 14", "hexadecimal")) << hex;
  }
  const std::string path = dir.Write("hex_pose.log", "O 0x64 200 0.5 0.9\n" + CmuLaserLine().Text());
  ExpectInputError([&] { ReadCmuLog(path); }, path, 1, "x");
}

TEST(CmuLogReaderBadInput, NegativeRange) {
  TempDir dir;
  CmuLaserLine l;
  l.ranges[179] = "-5";
  const std::string path = dir.Write("neg.log", l.Text() + l.Text());
  ExpectInputError([&] { ReadCmuLog(path); }, path, 1, "range 180");
}

TEST(CmuLogReaderBadInput, TruncatedLineNamesFirstMissingField) {
  TempDir dir;
  std::string line = CmuLaserLine().Text();
  // Keep "L", 6 pose fields and 43 ranges: range 44 is the first missing one.
  std::size_t pos = 0;
  for (int spaces = 0; spaces < 50; ++spaces) pos = line.find(' ', pos + 1);
  const std::string path = dir.Write("cut.log", kOdometryLine + kOdometryLine + line.substr(0, pos) + "\n");
  ExpectInputError([&] { ReadCmuLog(path); }, path, 3, "range 44");
}

TEST(CmuLogReaderBadInput, TooFewBeams) {
  TempDir dir;
  CmuLaserLine l;
  l.ranges.pop_back();  // 179 ranges: the timestamp lands in range 180's place
  const std::string path = dir.Write("179.log", l.Text());
  ExpectInputError([&] { ReadCmuLog(path); }, path, 1, "ts");
}

TEST(CmuLogReaderBadInput, TooManyBeams) {
  TempDir dir;
  CmuLaserLine l;
  l.ranges.push_back("300");
  const std::string path = dir.Write("181.log", CmuLaserLine().Text() + l.Text());
  ExpectInputError([&] { ReadCmuLog(path); }, path, 2, "field 189");
}

TEST(CmuLogReaderBadInput, NonNumericRange) {
  TempDir dir;
  CmuLaserLine l;
  l.ranges[4] = "12x";
  const std::string path = dir.Write("alpha.log", l.Text());
  ExpectInputError([&] { ReadCmuLog(path); }, path, 1, "range 5");
}

TEST(CmuLogReaderBadInput, NonNumericPose) {
  TempDir dir;
  std::string line = CmuLaserLine().Text();
  line.replace(line.find("0.500000"), 8, "north");
  const std::string path = dir.Write("theta.log", line);
  ExpectInputError([&] { ReadCmuLog(path); }, path, 1, "theta");
}

TEST(CmuLogReaderBadInput, NonNumericTimestamp) {
  TempDir dir;
  std::string line = CmuLaserLine().Text();
  line.replace(line.rfind("1.000000"), 8, "1.0.0");
  const std::string path = dir.Write("ts.log", line);
  ExpectInputError([&] { ReadCmuLog(path); }, path, 1, "ts");
}

TEST(CmuLogReaderBadInput, EmptyTraceWithOnlyOdometry) {
  TempDir dir;
  const std::string path = dir.Write("odom_only.log", kOdometryLine + kOdometryLine);
  ExpectInputError([&] { ReadCmuLog(path); }, path, 0, "L records");
}

TEST(CmuLogReaderBadInput, EmptyFile) {
  TempDir dir;
  const std::string path = dir.Write("empty.log", "");
  ExpectInputError([&] { ReadCmuLog(path); }, path, 0, "L records");
}

TEST(CmuLogReaderBadInput, UnknownRecordType) {
  TempDir dir;
  const std::string path = dir.Write("type.log", CmuLaserLine().Text() + "X 1 2 3 4\n");
  ExpectInputError([&] { ReadCmuLog(path); }, path, 2, "record type");
}

TEST(CmuLogReaderBadInput, TruncatedOdometryRecord) {
  TempDir dir;
  const std::string path = dir.Write("o_cut.log", "O 100 200\n" + CmuLaserLine().Text());
  ExpectInputError([&] { ReadCmuLog(path); }, path, 1, "theta");
}

TEST(CmuLogReaderBadInput, NanInOdometryRecord) {
  TempDir dir;
  const std::string path = dir.Write("o_nan.log", CmuLaserLine().Text() + "O 100 NaN 0.5 2.0\n");
  ExpectInputError([&] { ReadCmuLog(path); }, path, 2, "y");
}

TEST(CmuLogReaderBadInput, TimeGoesBackwards) {
  TempDir dir;
  CmuLaserLine early, late;
  early.ts = 5.0;
  late.ts = 4.0;
  const std::string path = dir.Write("back.log", early.Text() + late.Text());
  ExpectInputError([&] { ReadCmuLog(path); }, path, 2, "ts");
}

// A clock glitch of a real log (the Intel corrected log steps back 0.1 s)
// is read as logged and counted, not refused (record_fields.h).
TEST(CmuLogReader, SmallStepBackInTimeIsACountedGlitch) {
  TempDir dir;
  CmuLaserLine a, b, c, d;
  a.ts = 5.0;
  b.ts = 5.2;
  c.ts = 5.1;   // 0.1 s back
  d.ts = 5.05;  // 0.05 s back again
  const std::string path = dir.Write("glitch.log", a.Text() + b.Text() + c.Text() + d.Text());
  TraceReadStats stats;
  const SensorTrace trace = ReadCmuLog(path, {}, &stats);
  ASSERT_EQ(trace.scans.size(), 4u);
  EXPECT_DOUBLE_EQ(trace.scans[2].time_s, 5.1);  // kept as logged
  EXPECT_EQ(stats.time_glitches.count, 2);
  EXPECT_NEAR(stats.time_glitches.largest_step_s, 0.1, 1e-9);
  EXPECT_EQ(stats.time_glitches.first_line, 3);
  // Just under the limit is still a glitch; the limit itself is an error.
  CmuLaserLine e;
  e.ts = 5.2 - kMaxClockGlitchS;
  ExpectInputError([&] { ReadCmuLog(dir.Write("limit.log", a.Text() + b.Text() + e.Text())); }, dir.Path("limit.log"),
                   3, "ts");
}

// A log of another robot states its own mount in every record: it is
// measured from the laser poses, as CARMEN's reader does, and read.
TEST(CmuLogReader, AnotherRobotsMountIsMeasuredFromTheLaserPoses) {
  TempDir dir;
  CmuLaserLine l, m;
  l.laser_offset_cm = m.laser_offset_cm = 20.0;
  m.x_cm = 110.0;
  m.theta = 0.7;
  m.ts = 1.1;
  const std::string path = dir.Write("mount20.log", l.Text() + m.Text());
  TraceReadStats stats;
  const SensorTrace trace = ReadCmuLog(path, {}, &stats);
  EXPECT_DOUBLE_EQ(trace.geometry.offset_forward_m, 0.20);  // rounded to kMountResolutionM
  EXPECT_EQ(stats.laser_mount.samples, 2);
  CmuLogOptions other_robot;
  other_robot.laser_offset_forward_m = 0.30;  // --laser-offset overrides the file
  EXPECT_DOUBLE_EQ(ReadCmuLog(path, other_robot).geometry.offset_forward_m, 0.30);
}

TEST(CmuLogReaderBadInput, MountInconsistentWithinTheFile) {
  TempDir dir;
  CmuLaserLine l, m;
  m.laser_offset_cm = 30.0;  // 5 cm more than the first record's
  m.ts = 1.1;
  const std::string path = dir.Write("mount.log", l.Text() + m.Text());
  ExpectInputError([&] { ReadCmuLog(path); }, path, 2, "xl/yl");
  CmuLogOptions given;
  given.laser_offset_forward_m = 0.25;  // an override does not use the logged poses
  EXPECT_DOUBLE_EQ(ReadCmuLog(path, given).geometry.offset_forward_m, 0.25);
}

TEST(CmuLogReaderBadInput, LaserOffTheHeadingAxis) {
  TempDir dir;
  CmuLaserLine l;
  l.laser_lateral_cm = 3.0;  // LaserGeometry models a forward offset only
  const std::string path = dir.Write("sideways.log", l.Text());
  ExpectInputError([&] { ReadCmuLog(path); }, path, 1, "xl/yl");
}

TEST(CmuLogReaderBadInput, RotatedLaser) {
  TempDir dir;
  CmuLaserLine l;
  l.laser_theta_offset = 0.1;
  const std::string path = dir.Write("rot.log", l.Text());
  ExpectInputError([&] { ReadCmuLog(path); }, path, 1, "thetal");
}

TEST(CmuLogReaderBadInput, ADirectoryIsNotAnEmptyTrace) {
  TempDir dir;
  const std::string path = dir.Path("folder.log");
  std::filesystem::create_directory(path);
  EXPECT_TRUE(test::ThrowsInputError([&] { ReadCmuLog(path); }, 0, "", "is a directory, not a file"));
}

TEST(CmuLogReaderBadInput, MissingFile) {
  TempDir dir;
  const std::string path = dir.Path("absent.log");
  ExpectInputError([&] { ReadCmuLog(path); }, path, 0, "");
}

// ---- Real data (shared/data/wean). ----

struct RealLog {
  const char* name;
  std::size_t laser_records;
  long odometry_records;
};

class CmuRealLog : public ::testing::TestWithParam<RealLog> {};

TEST_P(CmuRealLog, LoadsWithoutErrorsAndPlausibleReadings) {
  const RealLog& log = GetParam();
  RC_REQUIRE_SHARED_DATA(std::string("wean/") + log.name);
  TraceReadStats stats;
  const SensorTrace trace = ReadCmuLog(test::SharedDataPath(std::string("wean/") + log.name), {}, &stats);
  EXPECT_EQ(trace.scans.size(), log.laser_records);
  EXPECT_EQ(stats.laser_records, static_cast<long>(log.laser_records));
  EXPECT_EQ(stats.odometry_records, log.odometry_records);
  // The max-range rule: every reading is either a real echo well short of
  // 81.83 m or one of the SICK status codes at/above it.
  const std::set<long> status_codes_cm = {8183, 8187, 8189, 8191};
  float min_range = 1e9f, max_echo = 0.0f;
  for (const LaserScan& s : trace.scans) {
    ASSERT_EQ(s.ranges_m.size(), 180u);
    for (float r : s.ranges_m) {
      min_range = std::min(min_range, r);
      if (r >= trace.geometry.max_range_m)
        EXPECT_EQ(status_codes_cm.count(std::lround(r * 100.0)), 1u) << r;
      else
        max_echo = std::max(max_echo, r);
    }
  }
  EXPECT_GT(min_range, 0.3f);  // no zero readings in these logs (37 cm is the least)
  EXPECT_LT(max_echo, 60.0f);  // largest real echo: 57.67 m, far from the codes
}

INSTANTIATE_TEST_SUITE_P(Wean, CmuRealLog,
                         ::testing::Values(RealLog{"robotdata1.log", 713, 1505}, RealLog{"robotdata2.log", 2251, 3126},
                                           RealLog{"robotdata3.log", 1241, 1735}, RealLog{"robotdata4.log", 600, 823}),
                         [](const auto& info) { return std::string(info.param.name).substr(0, 10); });

TEST(CmuRealLog, FirstRecordOfRobotdata1) {
  RC_REQUIRE_SHARED_DATA("wean/robotdata1.log");
  const SensorTrace trace = ReadCmuLog(test::SharedDataPath("wean/robotdata1.log"));
  const LaserScan& s = trace.scans.front();
  EXPECT_EQ(s.source_line, 1);
  EXPECT_NEAR(s.odometry.x, -0.94234001, 1e-12);
  EXPECT_NEAR(s.odometry.y, -1.39953995, 1e-12);
  EXPECT_DOUBLE_EQ(s.odometry.theta, -1.342158);
  EXPECT_DOUBLE_EQ(s.time_s, 0.025466);
  EXPECT_EQ(s.ranges_m[0], 0.66f);
  EXPECT_EQ(s.ranges_m[28], 5.30f);
  EXPECT_EQ(s.ranges_m[179], 0.70f);
}

// instruct.txt says "approximately 25 cm"; the logged laser poses say
// exactly 25 cm ahead, on the heading axis, in every record.
TEST(CmuRealLog, MeasuredLaserMountOfRobotdata1) {
  RC_REQUIRE_SHARED_DATA("wean/robotdata1.log");
  TraceReadStats stats;
  ReadCmuLog(test::SharedDataPath("wean/robotdata1.log"), {}, &stats);
  const LaserMountStats& mount = stats.laser_mount;
  EXPECT_EQ(mount.samples, 713);
  EXPECT_NEAR(mount.min_forward_m, 0.25, 2e-6);
  EXPECT_NEAR(mount.max_forward_m, 0.25, 2e-6);
  EXPECT_LT(mount.max_abs_lateral_m, 2e-6);
  EXPECT_LT(mount.max_abs_heading_rad, 1e-6);
}

}  // namespace
}  // namespace rc
