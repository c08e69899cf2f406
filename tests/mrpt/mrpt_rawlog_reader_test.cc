// MRPT .rawlog input: MRPT's own example log, both rawlog forms, and the
// corrupt and truncated archives that must become InputErrors.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>

#include <gtest/gtest.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CRawlog.h>
#include <mrpt/poses/CPosePDFGaussian.h>

#include "common/input_error.h"
#include "delibot/synthetic_world.h"
#include "mrpt/mrpt_test_data.h"
#include "support/input_error_expectations.h"
#include "support/temp_dir.h"
#include "traces/mrpt/mrpt_rawlog_reader.h"
#include "traces/mrpt/mrpt_rawlog_writer.h"
#include "traces/mrpt/mrpt_trace_dispatch.h"

namespace rc {
namespace {

std::vector<char> ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void WriteBytes(const std::string& path, const std::vector<char>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// The InputError that reading `path` raises (a test failure, and an empty
// error, when it reads cleanly).
InputError ReadingError(const std::string& path) {
  return test::InputErrorFrom([&] { ReadMrptRawlog(path); }, path);
}

SensorTrace SmallTrace() {
  const OccupancyGrid g = test::AsymmetricRoom();
  SensorTrace trace = test::DriveThrough(g, test::RoomTour(), 0.5, 0.02, 3).trace;
  for (auto& scan : trace.scans) scan.time_s += 1.2e9;                          // a realistic epoch time
  trace.scans[2].ranges_m[7] = static_cast<float>(trace.geometry.max_range_m);  // one "no return"
  return trace;
}

void ExpectSameTrace(const SensorTrace& expected, const SensorTrace& actual, double pose_tolerance) {
  ASSERT_EQ(expected.scans.size(), actual.scans.size());
  EXPECT_EQ(expected.geometry.beam_count, actual.geometry.beam_count);
  EXPECT_NEAR(expected.geometry.angle_min_rad, actual.geometry.angle_min_rad, 1e-6);
  EXPECT_NEAR(expected.geometry.angle_increment_rad, actual.geometry.angle_increment_rad, 1e-7);
  EXPECT_NEAR(expected.geometry.max_range_m, actual.geometry.max_range_m, 1e-6);
  EXPECT_NEAR(expected.geometry.offset_forward_m, actual.geometry.offset_forward_m, 1e-9);
  for (std::size_t k = 0; k < expected.scans.size(); ++k) {
    const LaserScan& a = expected.scans[k];
    const LaserScan& b = actual.scans[k];
    // The reader counts time from the first scan.
    EXPECT_NEAR(a.time_s - expected.scans[0].time_s, b.time_s, 1e-6) << "scan " << k;
    EXPECT_NEAR(a.odometry.x, b.odometry.x, pose_tolerance) << "scan " << k;
    EXPECT_NEAR(a.odometry.y, b.odometry.y, pose_tolerance) << "scan " << k;
    EXPECT_NEAR(WrapAngle(a.odometry.theta - b.odometry.theta), 0.0, pose_tolerance) << "scan " << k;
    ASSERT_EQ(a.ranges_m, b.ranges_m) << "scan " << k;
  }
}

TEST(MrptRawlogReader, ReadsMrptLocalizationDemoWithItsOwnGeometry) {
  RC_REQUIRE_MRPT_DATASET("localization_demo.rawlog");
  TraceReadStats stats;
  const SensorTrace trace = ReadMrptRawlog(test::MrptDatasetPath("localization_demo.rawlog"), {}, &stats);
  EXPECT_EQ(trace.format, "rawlog");
  EXPECT_EQ(trace.scans.size(), 37u);
  EXPECT_EQ(stats.laser_records, 37);
  EXPECT_EQ(stats.odometry_records, 37);  // one CActionRobotMovement2D per pair
  // The log's CObservation2DRangeScan: 361 ranges over 180 deg, right to
  // left, 80 m max range, laser 0.78 m ahead of the robot centre.
  EXPECT_EQ(trace.geometry.beam_count, 361);
  EXPECT_NEAR(trace.geometry.angle_min_rad, -kPi / 2, 1e-6);
  EXPECT_NEAR(trace.geometry.angle_increment_rad, kPi / 360, 1e-7);
  EXPECT_NEAR(trace.geometry.max_range_m, 80.0, 1e-6);
  EXPECT_NEAR(trace.geometry.offset_forward_m, 0.78, 1e-6);
  // The first action's odometry increment is (0.248 m, 0.019 m, 8.14 deg),
  // applied to the origin.
  EXPECT_NEAR(trace.scans[0].odometry.x, 0.248, 0.0005);
  EXPECT_NEAR(trace.scans[0].odometry.y, 0.019, 0.0005);
  EXPECT_NEAR(trace.scans[0].odometry.theta, 8.14 * kPi / 180, 0.0002);
  EXPECT_NEAR(trace.scans[0].ranges_m[0], 2.47, 1e-5);
  // Invalid readings (two in the first scan) become "no return".
  int no_return = 0;
  for (float r : trace.scans[0].ranges_m) no_return += r >= trace.geometry.max_range_m;
  EXPECT_EQ(no_return, 2);
  EXPECT_EQ(trace.scans[0].time_s, 0.0);
  for (std::size_t k = 1; k < trace.scans.size(); ++k) EXPECT_GE(trace.scans[k].time_s, trace.scans[k - 1].time_s);
  EXPECT_GT(trace.scans.back().time_s, 1.0);  // the log lasts seconds, kept to sub-second precision
}

TEST(MrptRawlogReader, BothFormsGiveTheSameTrace) {
  const test::TempDir dir;
  const SensorTrace trace = SmallTrace();
  const std::string actions = dir.Path("actions.rawlog");
  const std::string observations = dir.Path("observations.rawlog");
  WriteMrptRawlog(trace, actions, RawlogForm::kActionsObservations);
  WriteMrptRawlog(trace, observations, RawlogForm::kObservationsOnly);
  TraceReadStats stats;
  const SensorTrace from_observations = ReadMrptRawlog(observations, {}, &stats);
  EXPECT_EQ(stats.odometry_records, static_cast<long>(trace.scans.size()));  // CObservationOdometry
  ExpectSameTrace(trace, from_observations, 1e-9);                           // absolute poses, double precision
  // The actions form stores increments, composed back on reading.
  ExpectSameTrace(trace, ReadMrptRawlog(actions), 1e-5);
}

TEST(MrptRawlogReader, DispatcherPicksRawlogByExtensionOrName) {
  const test::TempDir dir;
  const SensorTrace trace = SmallTrace();
  const std::string path = dir.Path("dispatch.rawlog");
  const std::string renamed = dir.Path("dispatch.bin");
  WriteMrptRawlog(trace, path, RawlogForm::kObservationsOnly);
  std::filesystem::copy_file(path, renamed, std::filesystem::copy_options::overwrite_existing);
  TraceReadOptions options;
  EXPECT_EQ(ReadTraceWithRawlog(path, options).format, "rawlog");
  options.format = "rawlog";
  EXPECT_EQ(ReadTraceWithRawlog(renamed, options).scans.size(), trace.scans.size());
  options.expected_beam_count = 361;
  EXPECT_THROW(ReadTraceWithRawlog(path, options), InputError);  // the room trace has 180 beams
  options.format = "nonsense";
  EXPECT_THROW(ReadTraceWithRawlog(path, options), UsageError);
}

void ExpectInputErrorNamingFile(const std::string& path) {
  const InputError e = ReadingError(path);
  EXPECT_EQ(e.file(), path);
  EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
}

TEST(MrptRawlogReader, TruncatedArchivesAreInputErrors) {
  const test::TempDir dir;
  const std::string path = dir.Path("whole.rawlog");
  WriteMrptRawlog(SmallTrace(), path, RawlogForm::kActionsObservations);
  const std::vector<char> whole = ReadBytes(path);
  const std::string cut = dir.Path("cut.rawlog");
  // Cut inside the last object, inside the first, and after a few bytes.
  for (std::size_t keep : {whole.size() - 10, whole.size() / 2, std::size_t{300}, std::size_t{3}}) {
    WriteBytes(cut, std::vector<char>(whole.begin(), whole.begin() + static_cast<long>(keep)));
    SCOPED_TRACE("kept " + std::to_string(keep) + " of " + std::to_string(whole.size()) + " bytes");
    ExpectInputErrorNamingFile(cut);
  }
}

// Where the first CActionRobotMovement2D head in `bytes` ends (its version
// byte follows), or end() when there is none.
std::vector<char>::iterator FirstMovementHeadEnd(std::vector<char>& bytes) {
  const std::string head = std::string(1, static_cast<char>(0xa1)) + "mrpt::obs::CActionRobotMovement2D";
  const auto at = std::search(bytes.begin(), bytes.end(), head.begin(), head.end());
  return at == bytes.end() ? at : at + static_cast<long>(head.size());
}

// A tests/fuzz finding: MRPT dereferences a null pose PDF when a
// CActionRobotMovement2D names an estimation method it does not know.
TEST(MrptRawlogReader, UnknownEstimationMethodIsAnInputErrorNotACrash) {
  const test::TempDir dir;
  const std::string path = dir.Path("method.rawlog");
  WriteMrptRawlog(SmallTrace(), path, RawlogForm::kActionsObservations);
  std::vector<char> bytes = ReadBytes(path);
  const auto version = FirstMovementHeadEnd(bytes);
  ASSERT_NE(version, bytes.end());
  ASSERT_EQ(version[0], 7);  // the version this layout is known for
  version[1] = 5;            // estimationMethod = 5
  WriteBytes(path, bytes);
  const InputError e = ReadingError(path);
  EXPECT_EQ(e.field(), "estimationMethod");
}

// A tests/fuzz finding: the same null pose PDF, reached through a
// CActionCollection holding an action of version 6 (the earlier check read
// only version 7).
TEST(MrptRawlogReader, UnknownEstimationMethodOfAnOlderVersionIsAnInputError) {
  const test::TempDir dir;
  const std::string path = dir.Path("method6.rawlog");
  WriteMrptRawlog(SmallTrace(), path, RawlogForm::kActionsObservations);
  std::vector<char> bytes = ReadBytes(path);
  const auto version = FirstMovementHeadEnd(bytes);
  ASSERT_NE(version, bytes.end());
  version[0] = 6;
  version[1] = static_cast<char>(0xff);  // estimationMethod = 0xfeff, as in the finding
  version[2] = static_cast<char>(0xfe);
  WriteBytes(path, bytes);
  const InputError e = ReadingError(path);
  EXPECT_EQ(e.field(), "estimationMethod");
  EXPECT_NE(std::string(e.what()).find("version 6"), std::string::npos) << e.what();
}

// Scan matching (method 1) reads a pose PDF object; the odometry action's
// next object is its CPose2D increment, which is no CPosePDF: MRPT would
// get a null pointer and copy it.
TEST(MrptRawlogReader, ScanMatchingActionWithoutAPosePdfIsAnInputError) {
  const test::TempDir dir;
  const std::string path = dir.Path("nopdf.rawlog");
  WriteMrptRawlog(SmallTrace(), path, RawlogForm::kActionsObservations);
  std::vector<char> bytes = ReadBytes(path);
  const auto version = FirstMovementHeadEnd(bytes);
  ASSERT_NE(version, bytes.end());
  version[1] = 1;  // estimationMethod = 1, scan matching
  WriteBytes(path, bytes);
  const InputError e = ReadingError(path);
  EXPECT_EQ(e.field(), "poseChange");
  EXPECT_NE(std::string(e.what()).find("CPose2D"), std::string::npos) << e.what();
}

// A valid log whose motion comes from scan matching (a pose PDF, no
// odometer reading) is read, its increments taken from the PDF's mean.
TEST(MrptRawlogReader, ScanMatchingActionsAreRead) {
  const test::TempDir dir;
  const SensorTrace trace = SmallTrace();
  const std::string odometry_path = dir.Path("odometry.rawlog");
  WriteMrptRawlog(trace, odometry_path, RawlogForm::kActionsObservations);
  mrpt::obs::CRawlog rawlog;
  ASSERT_TRUE(rawlog.loadFromRawLogFile(odometry_path));
  std::size_t changed = 0;
  for (std::size_t i = 0; i < rawlog.size(); ++i) {
    if (rawlog.getType(i) != mrpt::obs::CRawlog::etActionCollection) continue;
    const auto movement = rawlog.getAsAction(i)->getBestMovementEstimation();
    ASSERT_TRUE(movement);
    auto pdf = mrpt::poses::CPosePDFGaussian::Create();
    pdf->mean = movement->rawOdometryIncrementReading;
    movement->estimationMethod = mrpt::obs::CActionRobotMovement2D::emScan2DMatching;
    movement->poseChange = mrpt::poses::CPosePDF::Ptr(pdf);
    ++changed;
  }
  ASSERT_GT(changed, 0u);
  const std::string matched_path = dir.Path("matched.rawlog");
  ASSERT_TRUE(rawlog.saveToRawLogFile(matched_path));
  ExpectSameTrace(ReadMrptRawlog(odometry_path), ReadMrptRawlog(matched_path), 1e-9);
}

// A tests/fuzz finding: a 2D scan declaring about 4e9 ranges made MRPT ask
// aligned_alloc for 16 GB, past the allocation budget, which saw only
// operator new. mrpt::aligned_malloc is now counted too.
TEST(MrptRawlogReader, ScanDeclaringBillionsOfRangesIsAnInputError) {
  const test::TempDir dir;
  const SensorTrace trace = SmallTrace();
  const std::string path = dir.Path("huge_scan.rawlog");
  WriteMrptRawlog(trace, path, RawlogForm::kObservationsOnly);
  std::vector<char> bytes = ReadBytes(path);
  const std::string scan_head = std::string(1, static_cast<char>(0xa2)) + "mrpt::obs::CObservation2DRangeScan";
  const std::string pose_head = std::string(1, static_cast<char>(0x94)) + "mrpt::poses::CPose3D";
  const auto scan = std::search(bytes.begin(), bytes.end(), scan_head.begin(), scan_head.end());
  const auto pose = std::search(scan, bytes.end(), pose_head.begin(), pose_head.end());
  ASSERT_NE(pose, bytes.end());
  // The range count follows the sensor pose: the first little-endian copy of
  // the beam count after the pose's head.
  const auto n = static_cast<std::uint32_t>(trace.geometry.beam_count);
  const std::string count{static_cast<char>(n & 0xFF), static_cast<char>((n >> 8) & 0xFF), '\0', '\0'};
  const auto at = std::search(pose + static_cast<long>(pose_head.size()), bytes.end(), count.begin(), count.end());
  ASSERT_NE(at, bytes.end());
  at[2] = static_cast<char>(0xF0);
  at[3] = static_cast<char>(0xF0);
  WriteBytes(path, bytes);
  const InputError e = ReadingError(path);
  EXPECT_NE(std::string(e.what()).find("would take more than"), std::string::npos) << e.what();
}

// A tests/fuzz finding (UBSan): MRPT copies a bool field's byte from the
// file, so rightToLeft may hold 9, which is no bool value.
TEST(MrptRawlogReader, ABoolFieldThatIsNeitherZeroNorOneIsAnInputError) {
  const test::TempDir dir;
  const std::string path = dir.Path("bool.rawlog");
  WriteMrptRawlog(SmallTrace(), path, RawlogForm::kObservationsOnly);
  std::vector<char> bytes = ReadBytes(path);
  const std::string head = std::string(1, static_cast<char>(0xa2)) + "mrpt::obs::CObservation2DRangeScan";
  const auto at = std::search(bytes.begin(), bytes.end(), head.begin(), head.end());
  ASSERT_NE(at, bytes.end());
  // version byte, aperture (float), then rightToLeft.
  char& right_to_left = at[static_cast<long>(head.size()) + 1 + 4];
  ASSERT_EQ(right_to_left, 1);
  right_to_left = 9;
  WriteBytes(path, bytes);
  const InputError e = ReadingError(path);
  EXPECT_NE(e.field().find("rightToLeft"), std::string::npos) << e.what();
}

// A tests/fuzz finding: a laser mount with a NaN coordinate passed every
// tolerance check (NaN compares false) into the trace's geometry.
TEST(MrptRawlogReader, ANonFiniteLaserMountIsAnInputError) {
  const test::TempDir dir;
  const std::string path = dir.Path("nan_mount.rawlog");
  SensorTrace trace = SmallTrace();
  trace.geometry.offset_forward_m = std::nan("");
  WriteMrptRawlog(trace, path, RawlogForm::kObservationsOnly);
  const InputError e = ReadingError(path);
  EXPECT_NE(e.field().find("sensorPose"), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("not finite"), std::string::npos) << e.what();
}

// A tests/fuzz finding: a CActionCollection whose object is not a CAction
// (here "nullptr") made MRPT copy a null pointer and dereference it.
TEST(MrptRawlogReader, ACollectionHoldingNoActionIsAnInputError) {
  const test::TempDir dir;
  const std::string path = dir.Path("null_action.rawlog");
  const std::string name = "mrpt::obs::CActionCollection";
  const std::string archive = std::string(1, static_cast<char>(0x80 | name.size())) + name + std::string(1, '\0') +
                              std::string("\x01\0\0\0", 4) + "\x87nullptr\x88" + "\x88";
  WriteBytes(path, std::vector<char>(archive.begin(), archive.end()));
  const InputError e = ReadingError(path);
  EXPECT_EQ(e.field(), "action");
  EXPECT_NE(std::string(e.what()).find("'nullptr'"), std::string::npos) << e.what();
}

TEST(MrptRawlogReader, TruncatedMrptDemoIsAnInputError) {
  const test::TempDir dir;
  RC_REQUIRE_MRPT_DATASET("localization_demo.rawlog");
  const std::vector<char> whole = ReadBytes(test::MrptDatasetPath("localization_demo.rawlog"));
  const std::string cut = dir.Path("demo_cut.rawlog");
  WriteBytes(cut, std::vector<char>(whole.begin(), whole.begin() + static_cast<long>(whole.size() * 2 / 3)));
  ExpectInputErrorNamingFile(cut);
}

TEST(MrptRawlogReader, CorruptAndForeignFilesAreInputErrors) {
  const test::TempDir dir;
  const std::string path = dir.Path("corrupt.rawlog");
  WriteBytes(path, std::vector<char>{'n', 'o', 't', ' ', 'a', ' ', 'r', 'a', 'w', 'l', 'o', 'g', '\n'});
  ExpectInputErrorNamingFile(path);
  // A valid archive whose class names are overwritten.
  WriteMrptRawlog(SmallTrace(), path, RawlogForm::kObservationsOnly);
  std::vector<char> bytes = ReadBytes(path);
  for (std::size_t i = 0; i < 64 && i < bytes.size(); ++i) bytes[i] = static_cast<char>(0xA5);
  WriteBytes(path, bytes);
  ExpectInputErrorNamingFile(path);
  WriteBytes(path, {});
  ExpectInputErrorNamingFile(path);
  ExpectInputErrorNamingFile(dir.Path("missing.rawlog"));
}

}  // namespace
}  // namespace rc
