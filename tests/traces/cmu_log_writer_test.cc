#include "traces/cmu_log_writer.h"

#include <cmath>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>

#include <gtest/gtest.h>

#include "common/text_fields.h"
#include "support/input_error_expectations.h"
#include "support/temp_dir.h"
#include "support/test_data.h"
#include "traces/cmu_laser_geometry.h"
#include "traces/cmu_log_reader.h"

namespace rc {
namespace {

using test::TempDir;

SensorTrace SimulatedTrace(int scans) {
  SensorTrace trace;
  trace.source_path = "simulated";
  trace.geometry = CmuLaserGeometry();
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> range(0.0f, 60.0f);
  std::uniform_real_distribution<double> coordinate(-40.0, 40.0);
  std::uniform_real_distribution<double> heading(-kPi, kPi);
  for (int k = 0; k < scans; ++k) {
    LaserScan s;
    s.time_s = 0.1 * k + 1.0 / 3.0;
    s.odometry = {coordinate(rng), coordinate(rng), heading(rng)};
    for (int b = 0; b < 180; ++b) s.ranges_m.push_back(range(rng));
    s.ranges_m[5] = 81.91f;  // a SICK status code, kept as is
    s.ranges_m[6] = 0.0f;
    trace.scans.push_back(s);
  }
  trace.scans[0].odometry.theta = kPi;  // heading at the wrap point
  return trace;
}

TEST(CmuLogWriter, RoundTripKeepsRangesExactlyAndPosesToPrintedPrecision) {
  TempDir dir;
  const SensorTrace original = SimulatedTrace(20);
  const std::string path = dir.Path("sim.log");
  CmuLogWriteOptions options;
  options.odometry_records = true;
  WriteCmuLog(original, path, options);
  TraceReadStats stats;
  const SensorTrace read = ReadCmuLog(path, {}, &stats);
  EXPECT_EQ(stats.odometry_records, 20);
  ASSERT_EQ(read.scans.size(), original.scans.size());
  for (std::size_t k = 0; k < read.scans.size(); ++k) {
    const LaserScan& a = original.scans[k];
    const LaserScan& b = read.scans[k];
    EXPECT_EQ(b.ranges_m, a.ranges_m) << "scan " << k;
    // %.6f in cm and rad: half of 1e-8 m and of 1e-6 rad / s.
    EXPECT_NEAR(b.odometry.x, a.odometry.x, 5.1e-9);
    EXPECT_NEAR(b.odometry.y, a.odometry.y, 5.1e-9);
    EXPECT_NEAR(b.odometry.theta, a.odometry.theta, 5.1e-7);
    EXPECT_NEAR(b.time_s, a.time_s, 5.1e-7);
    EXPECT_EQ(b.source_line, static_cast<long>(2 * k + 2));  // O then L
  }
  EXPECT_EQ(dir.FileCount(), 1);
}

TEST(CmuLogWriter, RealLogWritesBackAsWholeCentimetres) {
  RC_REQUIRE_SHARED_DATA("wean/robotdata1.log");
  TempDir dir;
  const std::string source = test::SharedDataPath("wean/robotdata1.log");
  const SensorTrace original = ReadCmuLog(source);
  const std::string path = dir.Path("copy.log");
  WriteCmuLog(original, path);
  const SensorTrace read = ReadCmuLog(path);
  ASSERT_EQ(read.scans.size(), 713u);
  for (std::size_t k = 0; k < read.scans.size(); ++k) {
    ASSERT_EQ(read.scans[k].ranges_m, original.scans[k].ranges_m);
    EXPECT_NEAR(read.scans[k].odometry.x, original.scans[k].odometry.x, 5.1e-9);
    EXPECT_EQ(read.scans[k].time_s, original.scans[k].time_s);
  }
  // The written range tokens are the logged ones ("66", not "66.0000026").
  std::ifstream a(source), b(path);
  std::string line_a, line_b;
  std::getline(a, line_a);
  std::getline(b, line_b);
  const auto fa = SplitFields(line_a), fb = SplitFields(line_b);
  ASSERT_EQ(fa.size(), fb.size());
  for (std::size_t i = 7; i < 187; ++i) EXPECT_EQ(fa[i], fb[i]) << "field " << i;
  for (std::size_t i = 1; i < 4; ++i) EXPECT_EQ(fa[i], fb[i]) << "field " << i;
}

TEST(CmuLogWriter, LaserPoseFollowsTheTraceMount) {
  TempDir dir;
  SensorTrace trace = SimulatedTrace(2);
  trace.geometry.offset_forward_m = 0.1;
  const std::string path = dir.Path("mount.log");
  WriteCmuLog(trace, path);
  // Read back, the mount is measured from the written laser poses.
  TraceReadStats stats;
  EXPECT_DOUBLE_EQ(ReadCmuLog(path, {}, &stats).geometry.offset_forward_m, 0.1);
  EXPECT_NEAR(stats.laser_mount.min_forward_m, 0.1, 1e-8);
  EXPECT_NEAR(stats.laser_mount.max_forward_m, 0.1, 1e-8);
}

TEST(CmuLogWriter, ShortRangeNoReturnStaysNoReturn) {
  TempDir dir;
  SensorTrace trace = SimulatedTrace(1);
  trace.geometry.max_range_m = 8.0;
  trace.scans[0].ranges_m.assign(180, 3.0f);
  trace.scans[0].ranges_m[10] = 8.0f;
  const std::string path = dir.Path("short.log");
  WriteCmuLog(trace, path);
  const SensorTrace read = ReadCmuLog(path);
  EXPECT_GE(read.scans[0].ranges_m[10], read.geometry.max_range_m);
  EXPECT_EQ(read.scans[0].ranges_m[11], 3.0f);
}

TEST(CmuLogWriter, RejectsValidReadingBeyondCmuRangeAndLeavesNoFile) {
  TempDir dir;
  SensorTrace trace = SimulatedTrace(1);
  trace.geometry.max_range_m = 100.0;
  trace.scans[0].ranges_m[3] = 90.0f;  // a real echo a CMU reader would take for "no return"
  EXPECT_THROW(WriteCmuLog(trace, dir.Path("far.log")), UsageError);
  EXPECT_EQ(dir.FileCount(), 0);
}

TEST(CmuLogWriter, RejectsNonCmuGeometry) {
  TempDir dir;
  SensorTrace trace = SimulatedTrace(1);
  trace.geometry.beam_count = 361;
  trace.geometry.angle_increment_rad = kPi / 360;
  trace.scans[0].ranges_m.assign(361, 1.0f);
  EXPECT_THROW(WriteCmuLog(trace, dir.Path("wide.log")), UsageError);
  EXPECT_EQ(dir.FileCount(), 0);
}

TEST(CmuLogWriter, RejectsNanRangeAndBackwardsTime) {
  TempDir dir;
  SensorTrace nan_trace = SimulatedTrace(2);
  nan_trace.scans[1].ranges_m[0] = NAN;
  EXPECT_THROW(WriteCmuLog(nan_trace, dir.Path("nan.log")), std::invalid_argument);
  SensorTrace back = SimulatedTrace(2);
  back.scans[1].time_s = -1.0;
  EXPECT_THROW(WriteCmuLog(back, dir.Path("back.log")), std::invalid_argument);
  EXPECT_EQ(dir.FileCount(), 0);
}

}  // namespace
}  // namespace rc
