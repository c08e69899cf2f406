#include "traces/carmen_log_reader.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "support/input_error_expectations.h"
#include "support/temp_dir.h"

namespace rc {
namespace {

using test::ExpectInputError;
using test::TempDir;

std::string Join(const std::vector<std::string>& fields) {
  std::string line;
  for (std::size_t i = 0; i < fields.size(); ++i) line += (i ? " " : "") + fields[i];
  return line + "\n";
}

std::string Num(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.9g", v);
  return text;
}

// One FLASER message; the laser pose is the odometry pose moved offset_m ahead.
struct Flaser {
  int declared_beams = 180;
  std::vector<std::string> ranges = std::vector<std::string>(180, "3.5");
  double odom_x = 1.0, odom_y = 2.0, odom_theta = 0.5;
  double offset_m = 0.0;
  double ts = 1000.25;

  std::vector<std::string> Fields() const {
    std::vector<std::string> f = {"FLASER", std::to_string(declared_beams)};
    f.insert(f.end(), ranges.begin(), ranges.end());
    for (double v : {odom_x + offset_m * std::cos(odom_theta), odom_y + offset_m * std::sin(odom_theta), odom_theta,
                     odom_x, odom_y, odom_theta, ts})
      f.push_back(Num(v));
    f.push_back("robot-host");
    f.push_back(Num(ts + 0.01));
    return f;
  }
  std::string Text() const { return Join(Fields()); }
};

Flaser WithBeams(int n) {
  Flaser l;
  l.declared_beams = n;
  l.ranges.assign(n, "3.5");
  return l;
}

// One ROBOTLASER1 message with a 0.5 deg, 361-beam laser 0.2 m ahead.
struct RobotLaser {
  int beams = 361;
  int remissions = 2;
  double ts = 50.0;
  double max_range = 30.0;

  std::vector<std::string> Fields() const {
    std::vector<std::string> f = {"ROBOTLASER1", "0", Num(-kPi / 2),        Num(kPi), Num(kPi / 360), Num(max_range),
                                  "0.01",        "0", std::to_string(beams)};
    f.insert(f.end(), beams, "4.25");
    f.push_back(std::to_string(remissions));
    f.insert(f.end(), remissions, "0.5");
    const double x = 3.0, y = -1.0, theta = kPi / 2;
    for (double v : {x, y + 0.2, theta, x, y, theta, 0.3, 0.0, 0.5, 0.2, 0.0, ts}) f.push_back(Num(v));
    f.push_back("host");
    f.push_back(Num(ts));
    return f;
  }
  std::string Text() const { return Join(Fields()); }
};

const std::string kHeader = "# CARMEN Logfile\n# file format is one message per line\n";
const std::string kOdom = "ODOM 1.0 2.0 0.5 0.1 0.0 0.0 999.9 robot-host 1000.0\n";

TEST(CarmenLogReader, FlaserRecordsWithDefaultGeometry) {
  TempDir dir;
  Flaser a, b;
  a.ranges[0] = "0.66";
  b.ts = 1000.5;
  b.odom_x = 1.5;
  const std::string path = dir.Write("run.clf", kHeader + "PARAM robot_use_sonar off\n" + kOdom + a.Text() +
                                                    "RAWLASER1 0 -1.57 3.14 0.017 81.9 0.01 0 0 0\n" + b.Text());
  TraceReadStats stats;
  const SensorTrace trace = ReadCarmenLog(path, {}, &stats);
  EXPECT_EQ(trace.format, "carmen");
  ASSERT_EQ(trace.scans.size(), 2u);
  EXPECT_EQ(stats.laser_records, 2);
  EXPECT_EQ(stats.odometry_records, 1);
  EXPECT_EQ(stats.skipped_records, 2);  // PARAM and RAWLASER1
  const LaserGeometry& g = trace.geometry;
  EXPECT_EQ(g.beam_count, 180);
  EXPECT_DOUBLE_EQ(g.angle_min_rad, -kPi / 2);
  EXPECT_DOUBLE_EQ(g.angle_increment_rad, kPi / 180);
  EXPECT_DOUBLE_EQ(g.max_range_m, 81.83);
  EXPECT_NEAR(g.offset_forward_m, 0.0, 1e-12);
  const LaserScan& s = trace.scans[0];
  EXPECT_EQ(s.source_line, 5);
  EXPECT_DOUBLE_EQ(s.odometry.x, 1.0);
  EXPECT_DOUBLE_EQ(s.odometry.y, 2.0);
  EXPECT_DOUBLE_EQ(s.odometry.theta, 0.5);
  EXPECT_DOUBLE_EQ(s.time_s, 1000.25);
  EXPECT_EQ(s.ranges_m[0], 0.66f);  // metres already
  EXPECT_DOUBLE_EQ(trace.scans[1].odometry.x, 1.5);
}

TEST(CarmenLogReader, OddBeamCountsSpanBothEnds) {
  TempDir dir;
  const SensorTrace t181 = ReadCarmenLog(dir.Write("181.clf", WithBeams(181).Text()));
  EXPECT_DOUBLE_EQ(t181.geometry.angle_increment_rad, kPi / 180);
  EXPECT_NEAR(t181.geometry.BeamAngle(180), kPi / 2, 1e-12);
  const SensorTrace t361 = ReadCarmenLog(dir.Write("361.clf", WithBeams(361).Text()));
  EXPECT_DOUBLE_EQ(t361.geometry.angle_increment_rad, kPi / 360);
  EXPECT_NEAR(t361.geometry.BeamAngle(360), kPi / 2, 1e-12);
  const SensorTrace t360 = ReadCarmenLog(dir.Write("360.clf", WithBeams(360).Text()));
  EXPECT_DOUBLE_EQ(t360.geometry.angle_increment_rad, kPi / 360);
}

TEST(CarmenLogReader, ParamsSetFlaserResolutionAndMaxRange) {
  TempDir dir;
  const std::string path = dir.Write("params.clf",
                                     "PARAM laser_front_laser_resolution 0.5 0.0 host 0.0\n"
                                     "PARAM robot_front_laser_max 50.0\n" +
                                         WithBeams(361).Text());
  const SensorTrace trace = ReadCarmenLog(path);
  EXPECT_DOUBLE_EQ(trace.geometry.angle_increment_rad, 0.5 * kPi / 180);
  EXPECT_DOUBLE_EQ(trace.geometry.max_range_m, 50.0);
}

TEST(CarmenLogReader, MountDerivedFromLaserPose) {
  TempDir dir;
  Flaser a, b;
  a.offset_m = b.offset_m = 0.12;
  b.odom_theta = -2.0;
  b.ts = 1001.0;
  TraceReadStats stats;
  const SensorTrace trace = ReadCarmenLog(dir.Write("mount.clf", a.Text() + b.Text()), {}, &stats);
  EXPECT_NEAR(trace.geometry.offset_forward_m, 0.12, 1e-8);
  EXPECT_NEAR(stats.laser_mount.max_forward_m, 0.12, 1e-8);
  EXPECT_LT(stats.laser_mount.max_abs_lateral_m, 1e-8);
}

TEST(CarmenLogReader, ExplicitMountIgnoresLoggedLaserPose) {
  TempDir dir;
  Flaser a, b;
  b.offset_m = 3.0;  // e.g. a corrected pose, not odometry plus mount
  b.ts = 1001.0;
  CarmenLogOptions options;
  options.laser_offset_forward_m = 0.2;
  const SensorTrace trace = ReadCarmenLog(dir.Write("corrected.clf", a.Text() + b.Text()), options);
  EXPECT_DOUBLE_EQ(trace.geometry.offset_forward_m, 0.2);
  EXPECT_EQ(trace.scans.size(), 2u);
}

TEST(CarmenLogReader, RobotLaserCarriesItsGeometry) {
  TempDir dir;
  RobotLaser a, b;
  b.ts = 50.1;
  const SensorTrace trace = ReadCarmenLog(dir.Write("robotlaser.clf", kOdom + a.Text() + b.Text()));
  ASSERT_EQ(trace.scans.size(), 2u);
  EXPECT_EQ(trace.geometry.beam_count, 361);
  EXPECT_DOUBLE_EQ(trace.geometry.angle_min_rad, std::stod(Num(-kPi / 2)));
  EXPECT_DOUBLE_EQ(trace.geometry.angle_increment_rad, std::stod(Num(kPi / 360)));
  EXPECT_DOUBLE_EQ(trace.geometry.max_range_m, 30.0);
  EXPECT_NEAR(trace.geometry.offset_forward_m, 0.2, 1e-7);
  EXPECT_DOUBLE_EQ(trace.scans[0].odometry.x, 3.0);
  EXPECT_DOUBLE_EQ(trace.scans[0].odometry.y, -1.0);
  EXPECT_EQ(trace.scans[0].ranges_m[360], 4.25f);
  EXPECT_DOUBLE_EQ(trace.scans[1].time_s, 50.1);
}

// ---- Bad input ----

TEST(CarmenLogReaderBadInput, NanRange) {
  TempDir dir;
  Flaser l;
  l.ranges[36] = "nan";
  const std::string path = dir.Write("nan.clf", kHeader + l.Text());
  ExpectInputError([&] { ReadCarmenLog(path); }, path, 3, "range 37");
}

TEST(CarmenLogReaderBadInput, InfRange) {
  TempDir dir;
  Flaser l;
  l.ranges[179] = "inf";
  const std::string path = dir.Write("inf.clf", l.Text());
  ExpectInputError([&] { ReadCarmenLog(path); }, path, 1, "range 180");
}

TEST(CarmenLogReaderBadInput, NegativeRange) {
  TempDir dir;
  Flaser l;
  l.ranges[0] = "-0.01";
  const std::string path = dir.Write("neg.clf", l.Text());
  ExpectInputError([&] { ReadCarmenLog(path); }, path, 1, "range 1");
}

TEST(CarmenLogReaderBadInput, TruncatedLine) {
  TempDir dir;
  auto f = Flaser().Fields();
  f.resize(2 + 180 + 4);  // ends after odom_x
  const std::string path = dir.Write("cut.clf", kOdom + Join(f));
  ExpectInputError([&] { ReadCarmenLog(path); }, path, 2, "odom_y");
}

// The count is wrong, not the trailer it shifts: the line's length, read
// from its host name, says how many ranges it holds.
TEST(CarmenLogReaderBadInput, FewerRangesThanDeclared) {
  TempDir dir;
  Flaser l;
  l.ranges.pop_back();  // declares 180, carries 179
  const std::string path = dir.Write("179.clf", l.Text());
  ExpectInputError([&] { ReadCarmenLog(path); }, path, 1, "num_readings");
  EXPECT_TRUE(test::ThrowsInputError([&] { ReadCarmenLog(path); }, 1, "num_readings",
                                     "says 180 readings, but the line holds 179"));
}

TEST(CarmenLogReaderBadInput, MoreRangesThanDeclared) {
  TempDir dir;
  Flaser l = WithBeams(181);
  l.declared_beams = 180;
  const std::string path = dir.Write("181.clf", Flaser().Text() + l.Text());
  EXPECT_TRUE(test::ThrowsInputError([&] { ReadCarmenLog(path); }, 2, "num_readings",
                                     "says 180 readings, but the line holds 181"));
}

TEST(CarmenLogReaderBadInput, BeamCountChangesBetweenRecords) {
  TempDir dir;
  Flaser b = WithBeams(181);
  b.ts = 2000.0;
  const std::string path = dir.Write("mixed_n.clf", Flaser().Text() + b.Text());
  ExpectInputError([&] { ReadCarmenLog(path); }, path, 2, "num_readings");
}

TEST(CarmenLogReaderBadInput, NonNumericField) {
  TempDir dir;
  auto f = Flaser().Fields();
  f[2 + 180 + 5] = "west";  // odom_theta
  const std::string path = dir.Write("alpha.clf", Join(f));
  ExpectInputError([&] { ReadCarmenLog(path); }, path, 1, "odom_theta");
}

TEST(CarmenLogReaderBadInput, NonNumericBeamCount) {
  TempDir dir;
  auto f = Flaser().Fields();
  f[1] = "many";
  const std::string path = dir.Write("n.clf", Join(f));
  ExpectInputError([&] { ReadCarmenLog(path); }, path, 1, "num_readings");
}

TEST(CarmenLogReader, AByteOrderMarkBeforeTheFirstMessageIsSkipped) {
  TempDir dir;
  for (const std::string& first : {kHeader, kOdom, Flaser().Text()}) {
    const std::string path = dir.Write("bom.clf", "\xEF\xBB\xBF" + first + Flaser().Text());
    EXPECT_EQ(ReadCarmenLog(path).scans.size(), first == kHeader || first == kOdom ? 1u : 2u) << first;
  }
}

TEST(CarmenLogReaderBadInput, EmptyTrace) {
  TempDir dir;
  const std::string path = dir.Write("odom_only.clf", kHeader + "PARAM a b\n" + kOdom);
  ExpectInputError([&] { ReadCarmenLog(path); }, path, 0, "FLASER or ROBOTLASER1 records");
}

TEST(CarmenLogReaderBadInput, MixedLaserMessages) {
  TempDir dir;
  RobotLaser r;
  r.ts = 2000.0;
  const std::string path = dir.Write("mixed.clf", Flaser().Text() + r.Text());
  ExpectInputError([&] { ReadCarmenLog(path); }, path, 2, "message");
}

TEST(CarmenLogReaderBadInput, MountChangesBetweenRecords) {
  TempDir dir;
  Flaser b;
  b.offset_m = 0.5;
  b.ts = 2000.0;
  const std::string path = dir.Write("mount.clf", Flaser().Text() + b.Text());
  ExpectInputError([&] { ReadCarmenLog(path); }, path, 2, "x/y");
}

TEST(CarmenLogReaderBadInput, TimeGoesBackwards) {
  TempDir dir;
  Flaser b;
  b.ts = 10.0;
  const std::string path = dir.Write("back.clf", Flaser().Text() + b.Text());
  ExpectInputError([&] { ReadCarmenLog(path); }, path, 2, "timestamp");
}

TEST(CarmenLogReaderBadInput, NotACarmenLine) {
  TempDir dir;
  const std::string path = dir.Write("cmu.clf", "L 1 2 3\n");
  ExpectInputError([&] { ReadCarmenLog(path); }, path, 1, "message");
}

TEST(CarmenLogReaderBadInput, TruncatedOdom) {
  TempDir dir;
  const std::string path = dir.Write("odom.clf", "ODOM 1.0 2.0 0.5 0.1 0.0 0.0 999.9\n");
  ExpectInputError([&] { ReadCarmenLog(path); }, path, 1, "hostname");
}

TEST(CarmenLogReaderBadInput, ParamChangesGeometryAfterFirstScan) {
  TempDir dir;
  Flaser b;
  b.ts = 2000.0;
  const std::string path = dir.Write("late_param.clf", Flaser().Text() + "PARAM robot_front_laser_max 40\n" + b.Text());
  ExpectInputError([&] { ReadCarmenLog(path); }, path, 2, "robot_front_laser_max");
}

TEST(CarmenLogReaderBadInput, RobotLaserCutInRemissions) {
  TempDir dir;
  auto f = RobotLaser().Fields();
  f.resize(9 + 361 + 1 + 1);  // declares 2 remissions, carries 1
  const std::string path = dir.Write("rl_cut.clf", Join(f));
  ExpectInputError([&] { ReadCarmenLog(path); }, path, 1, "remission 2");
}

// As for FLASER, a wrong count is reported as itself, not as the remission,
// trailing field or num_remissions that it shifts: num_readings (field 9)
// against the ranges present, num_remissions against the remissions.
TEST(CarmenLogReaderBadInput, RobotLaserReadingCountDisagreesWithRanges) {
  TempDir dir;
  for (int remissions : {2, 0}) {
    RobotLaser r;
    r.remissions = remissions;
    for (const char* declared : {"362", "360"}) {
      auto f = r.Fields();
      f[8] = declared;  // the line carries 361 ranges
      const std::string path = dir.Write("rl_n.clf", Join(f));
      ExpectInputError([&] { ReadCarmenLog(path); }, path, 1, "num_readings");
      EXPECT_TRUE(test::ThrowsInputError([&] { ReadCarmenLog(path); }, 1, "num_readings",
                                         "says " + std::string(declared) + " readings, but the line holds 361"))
          << remissions << " remissions";
    }
  }
  // More readings stated than the line has values for.
  auto f = RobotLaser().Fields();
  f[8] = "400";
  const std::string path = dir.Write("rl_400.clf", Join(f));
  ExpectInputError([&] { ReadCarmenLog(path); }, path, 1, "num_readings");
}

TEST(CarmenLogReaderBadInput, RobotLaserRemissionCountDisagreesWithRemissions) {
  TempDir dir;
  for (const char* declared : {"3", "1"}) {
    auto f = RobotLaser().Fields();  // 2 remissions
    f[9 + 361] = declared;
    const std::string path = dir.Write("rl_m.clf", Join(f));
    ExpectInputError([&] { ReadCarmenLog(path); }, path, 1, "num_remissions");
    EXPECT_TRUE(test::ThrowsInputError([&] { ReadCarmenLog(path); }, 1, "num_remissions",
                                       "says " + std::string(declared) + " remissions, but the line holds 2"));
  }
  RobotLaser none;
  none.remissions = 0;
  auto f = none.Fields();
  f[9 + 361] = "1";
  const std::string path = dir.Write("rl_m0.clf", Join(f));
  EXPECT_TRUE(test::ThrowsInputError([&] { ReadCarmenLog(path); }, 1, "num_remissions",
                                     "says 1 remissions, but the line holds 0"));
}

}  // namespace
}  // namespace rc
