#include "traces/trace_reader.h"

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "support/input_error_expectations.h"
#include "support/temp_dir.h"
#include "support/test_data.h"

namespace rc {
namespace {

using test::ExpectInputError;
using test::TempDir;

std::string Repeat(const std::string& token, int n) {
  std::string out;
  for (int i = 0; i < n; ++i) out += " " + token;
  return out;
}

const std::string kCmuLaser = "L 100 200 0 125 200 0" + Repeat("300", 180) + " 1.5\n";
const std::string kRowild = "100 200 0" + Repeat("300", 180) + "\n";
const std::string kFlaser361 = "FLASER 361" + Repeat("3.0", 361) + " 1 2 0 1 2 0 10.0 host 10.1\n";

TEST(DetectTraceFormat, ByContentNotExtension) {
  TempDir dir;
  EXPECT_EQ(DetectTraceFormat(dir.Write("a.log", "\nO 1 2 3 4\n" + kCmuLaser)), "cmu");
  EXPECT_EQ(DetectTraceFormat(dir.Write("b.txt", kRowild)), "rowild");
  EXPECT_EQ(DetectTraceFormat(dir.Write("c.clf", "# CARMEN Logfile\n" + kFlaser361)), "carmen");
  // CARMEN's own logger names its files .log.
  EXPECT_EQ(DetectTraceFormat(dir.Write("d.log", "PARAM robot_use_laser on\n" + kFlaser361)), "carmen");
}

TEST(DetectTraceFormat, SkipsAByteOrderMark) {
  TempDir dir;
  const std::string bom = "\xEF\xBB\xBF";
  EXPECT_EQ(DetectTraceFormat(dir.Write("a.log", bom + "O 1 2 3 4\n" + kCmuLaser)), "cmu");
  EXPECT_EQ(DetectTraceFormat(dir.Write("b.txt", bom + kRowild)), "rowild");
  EXPECT_EQ(DetectTraceFormat(dir.Write("c.clf", bom + kFlaser361)), "carmen");
  EXPECT_EQ(ReadTrace(dir.Write("d.txt", bom + kRowild + kRowild), {}).scans.size(), 2u);
}

TEST(DetectTraceFormat, ADirectoryIsNotAnEmptyTrace) {
  TempDir dir;
  const std::string path = dir.Path("folder.log");
  std::filesystem::create_directory(path);
  EXPECT_TRUE(test::ThrowsInputError([&] { DetectTraceFormat(path); }, 0, "", "is a directory, not a file"));
  for (const char* format : {"cmu", "rowild", "carmen"}) {
    TraceReadOptions o;
    o.format = format;
    EXPECT_TRUE(test::ThrowsInputError([&] { ReadTrace(path, o); }, 0, "", "is a directory")) << format;
    EXPECT_TRUE(test::ThrowsInputError([&] { OpenTraceStream(path, o); }, 0, "", "is a directory")) << format;
  }
}

TEST(DetectTraceFormat, UnknownContentIsAnError) {
  TempDir dir;
  const std::string path = dir.Write("map.dat", "\nrobot_specifications->resolution 10\n");
  ExpectInputError([&] { DetectTraceFormat(path); }, path, 2, "format");
  const std::string empty = dir.Write("empty.log", "\n");
  ExpectInputError([&] { DetectTraceFormat(empty); }, empty, 0, "format");
}

TEST(DetectTraceFormat, RowildShapedLineWithText) {
  TempDir dir;
  const std::string path = dir.Write("bad.txt", "100 200 zero" + Repeat("300", 180) + "\n");
  ExpectInputError([&] { DetectTraceFormat(path); }, path, 1, "field 3");
}

TEST(ReadTrace, DispatchesOnDetectedFormat) {
  TempDir dir;
  TraceReadOptions options;
  EXPECT_EQ(ReadTrace(dir.Write("a.log", kCmuLaser), options).format, "cmu");
  EXPECT_EQ(ReadTrace(dir.Write("b.txt", kRowild), options).format, "rowild");
  const SensorTrace carmen = ReadTrace(dir.Write("c.clf", kFlaser361), options);
  EXPECT_EQ(carmen.format, "carmen");
  EXPECT_EQ(carmen.geometry.beam_count, 361);
}

TEST(ReadTrace, ExplicitFormatOverridesDetection) {
  TempDir dir;
  TraceReadOptions options;
  options.format = "rowild";
  const std::string path = dir.Write("a.log", kCmuLaser);
  ExpectInputError([&] { ReadTrace(path, options); }, path, 1, "field 184");  // 188 fields, not 183
}

TEST(ReadTrace, WrongBeamCountForTheRun) {
  TempDir dir;
  TraceReadOptions options;
  options.expected_beam_count = 180;
  const std::string path = dir.Write("wide.clf", "# log\n" + kFlaser361);
  ExpectInputError([&] { ReadTrace(path, options); }, path, 2, "beam count");
  EXPECT_EQ(ReadTrace(dir.Write("ok.log", kCmuLaser), options).scans.size(), 1u);
}

TEST(ReadTrace, UnknownFormatNameIsAUsageError) {
  TempDir dir;
  TraceReadOptions options;
  options.format = "bag";
  EXPECT_THROW(ReadTrace(dir.Write("a.log", kCmuLaser), options), UsageError);
  options.format = "auto";
  options.expected_beam_count = -1;
  EXPECT_THROW(ReadTrace(dir.Write("b.log", kCmuLaser), options), UsageError);
}

TEST(ReadTrace, RealLogsByAutoDetection) {
  RC_REQUIRE_SHARED_DATA("wean/robotdata3.log");
  RC_REQUIRE_SHARED_DATA("wean/rowild_log1.txt");
  TraceReadOptions options;
  options.expected_beam_count = 180;
  TraceReadStats stats;
  EXPECT_EQ(ReadTrace(test::SharedDataPath("wean/robotdata3.log"), options, &stats).scans.size(), 1241u);
  EXPECT_EQ(stats.odometry_records, 1735);
  EXPECT_EQ(ReadTrace(test::SharedDataPath("wean/rowild_log1.txt"), options).format, "rowild");
}

// ---- Streaming: the same records as ReadTrace, one at a time. ----

std::string CmuLaser(double ts, double x_cm) {
  return "L " + std::to_string(x_cm) + " 200 0 " + std::to_string(x_cm + 25) + " 200 0" + Repeat("300", 180) + " " +
         std::to_string(ts) + "\n";
}

TEST(OpenTraceStream, ServesTheRecordsReadTraceReturns) {
  TempDir dir;
  std::string text;
  for (int k = 0; k < 5; ++k) text += "O 1 2 0 " + std::to_string(k) + "\n" + CmuLaser(k + 0.5, 100 + k);
  const std::string path = dir.Write("five.log", text);
  const SensorTrace whole = ReadTrace(path, {});
  TraceReadStats stats;
  std::unique_ptr<ScanSource> stream = OpenTraceStream(path, {}, &stats);
  EXPECT_EQ(stream->size(), 5u);
  EXPECT_EQ(stream->format(), "cmu");
  EXPECT_EQ(stream->geometry().offset_forward_m, whole.geometry.offset_forward_m);
  EXPECT_EQ(stats.laser_records, 5);
  EXPECT_EQ(stats.odometry_records, 5);
  for (int pass = 0; pass < 2; ++pass) {
    LaserScan scan;
    for (const LaserScan& expected : whole.scans) {
      ASSERT_TRUE(stream->Next(scan));
      EXPECT_EQ(scan.time_s, expected.time_s);
      EXPECT_EQ(scan.source_line, expected.source_line);
      EXPECT_EQ(scan.odometry.x, expected.odometry.x);
      EXPECT_EQ(scan.ranges_m, expected.ranges_m);
    }
    EXPECT_FALSE(stream->Next(scan));
    stream->Rewind();
  }
}

// Every bad-input error comes when the stream is opened, before a run has
// taken (or written) anything.
TEST(OpenTraceStream, ValidatesTheWholeFileWhenOpened) {
  TempDir dir;
  const std::string path = dir.Write("bad.log", CmuLaser(1, 100) + CmuLaser(2, 101) + "L 102 200 nan 127 200 0" +
                                                    Repeat("300", 180) + " 3\n");
  ExpectInputError([&] { OpenTraceStream(path, {}); }, path, 3, "theta");
  const std::string empty = dir.Write("empty.log", "O 1 2 0 1\n");
  ExpectInputError([&] { OpenTraceStream(empty, {}); }, empty, 0, "L records");
}

TEST(OpenTraceStream, AFileThatChangesWhileReadIsAnInputError) {
  TempDir dir;
  const std::string path = dir.Write("grow.log", CmuLaser(1, 100) + CmuLaser(2, 101));
  std::unique_ptr<ScanSource> stream = OpenTraceStream(path, {});
  dir.Write("grow.log", CmuLaser(1, 100) + CmuLaser(2, 101) + CmuLaser(3, 102));
  stream->Rewind();
  LaserScan scan;
  ASSERT_TRUE(stream->Next(scan));
  ASSERT_TRUE(stream->Next(scan));
  EXPECT_THROW(stream->Next(scan), InputError);
}

TEST(OpenTraceStream, LaserOffsetOverridesEveryFormat) {
  TempDir dir;
  TraceReadOptions options;
  options.laser_offset_forward_m = 0.4;
  EXPECT_EQ(OpenTraceStream(dir.Write("a.log", kCmuLaser), options)->geometry().offset_forward_m, 0.4);
  EXPECT_EQ(OpenTraceStream(dir.Write("b.txt", kRowild), options)->geometry().offset_forward_m, 0.4);
  EXPECT_EQ(ReadTrace(dir.Write("c.clf", kFlaser361), options).geometry.offset_forward_m, 0.4);
  options.laser_offset_forward_m = -1.0;
  EXPECT_THROW(OpenTraceStream(dir.Path("a.log"), options), UsageError);
}

}  // namespace
}  // namespace rc
