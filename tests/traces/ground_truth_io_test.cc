#include "traces/ground_truth_io.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <gtest/gtest.h>

#include "support/input_error_expectations.h"
#include "support/temp_dir.h"

namespace rc {
namespace {

using test::ExpectInputError;
using test::TempDir;

SensorTrace TraceWithTimes(std::initializer_list<double> times) {
  SensorTrace trace;
  trace.source_path = "sim.log";
  long line = 1;
  for (double t : times) {
    LaserScan s;
    s.time_s = t;
    s.source_line = line++;
    trace.scans.push_back(s);
  }
  return trace;
}

TEST(GroundTruthIo, WriteThenReadIsExact) {
  TempDir dir;
  const std::vector<GroundTruthPose> poses = {{0.1, {1.0 / 3.0, -2.5e-7, kPi - 1e-12}, 0},
                                              {1234567890.123456, {40.0000000001, 1e-300, -3.0}, 0}};
  const std::string path = dir.Path("truth.txt");
  WriteGroundTruth(path, poses);
  std::ifstream in(path);
  std::string first_line;
  std::getline(in, first_line);
  EXPECT_EQ(first_line, "# t_s x_m y_m theta_rad");
  const GroundTruth truth = ReadGroundTruth(path);
  ASSERT_EQ(truth.poses.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(truth.poses[k].time_s, poses[k].time_s);
    EXPECT_EQ(truth.poses[k].pose.x, poses[k].pose.x);
    EXPECT_EQ(truth.poses[k].pose.y, poses[k].pose.y);
    EXPECT_EQ(truth.poses[k].pose.theta, poses[k].pose.theta);
    EXPECT_EQ(truth.poses[k].source_line, static_cast<long>(k + 2));
  }
  EXPECT_EQ(dir.FileCount(), 1);  // no temporary left behind
}

TEST(GroundTruthIo, WriterRejectsNonFinitePoseAndLeavesNoFile) {
  TempDir dir;
  const std::string path = dir.Path("truth.txt");
  EXPECT_THROW(WriteGroundTruth(path, {{0.0, {0.0, NAN, 0.0}, 0}}), std::invalid_argument);
  EXPECT_EQ(dir.FileCount(), 0);
}

// With the mark, the '#' header line was taken for a 5-field pose.
TEST(GroundTruthIo, AByteOrderMarkBeforeTheHeaderIsSkipped) {
  TempDir dir;
  const std::string path = dir.Write("gt.txt", "\xEF\xBB\xBF# t_s x_m y_m theta_rad\n0.5 1 2 3\n");
  const GroundTruth truth = ReadGroundTruth(path);
  ASSERT_EQ(truth.poses.size(), 1u);
  EXPECT_EQ(truth.poses[0].source_line, 2);
  const std::string no_header = dir.Write("gt2.txt",
                                          "\xEF\xBB\xBF"
                                          "0.5 1 2 3\n");
  EXPECT_EQ(ReadGroundTruth(no_header).poses[0].time_s, 0.5);
}

TEST(GroundTruthIoBadInput, ADirectoryIsNotAnEmptyFile) {
  TempDir dir;
  const std::string path = dir.Path("truth");
  std::filesystem::create_directory(path);
  EXPECT_TRUE(test::ThrowsInputError([&] { ReadGroundTruth(path); }, 0, "", "is a directory, not a file"));
}

TEST(GroundTruthIoBadInput, NanValue) {
  TempDir dir;
  const std::string path = dir.Write("gt.txt", "# t x y theta\n0 1 2 3\n1 nan 2 3\n");
  ExpectInputError([&] { ReadGroundTruth(path); }, path, 3, "x");
}

TEST(GroundTruthIoBadInput, InfValue) {
  TempDir dir;
  const std::string path = dir.Write("gt.txt", "0 1 2 -inf\n");
  ExpectInputError([&] { ReadGroundTruth(path); }, path, 1, "theta");
}

TEST(GroundTruthIoBadInput, TruncatedLine) {
  TempDir dir;
  const std::string path = dir.Write("gt.txt", "0 1 2 3\n1 1 2\n");
  ExpectInputError([&] { ReadGroundTruth(path); }, path, 2, "theta");
}

TEST(GroundTruthIoBadInput, ExtraField) {
  TempDir dir;
  const std::string path = dir.Write("gt.txt", "0 1 2 3 4\n");
  ExpectInputError([&] { ReadGroundTruth(path); }, path, 1, "field 5");
}

TEST(GroundTruthIoBadInput, NonNumericField) {
  TempDir dir;
  const std::string path = dir.Write("gt.txt", "t0 1 2 3\n");
  ExpectInputError([&] { ReadGroundTruth(path); }, path, 1, "t");
}

TEST(GroundTruthIoBadInput, EmptyFile) {
  TempDir dir;
  const std::string path = dir.Write("gt.txt", "# t_s x_m y_m theta_rad\n");
  ExpectInputError([&] { ReadGroundTruth(path); }, path, 0, "poses");
}

TEST(CheckGroundTruthMatches, AcceptsOnePosePerRecordAtTheSameTimes) {
  TempDir dir;
  const std::string path = dir.Write("gt.txt", "# header\n0.5 1 2 3\n0.75 1 2 3\n");
  EXPECT_NO_THROW(CheckGroundTruthMatches(TraceWithTimes({0.5, 0.75}), ReadGroundTruth(path)));
}

TEST(CheckGroundTruthMatches, CountMismatch) {
  TempDir dir;
  const std::string path = dir.Write("gt.txt", "0.5 1 2 3\n");
  const GroundTruth truth = ReadGroundTruth(path);
  ExpectInputError([&] { CheckGroundTruthMatches(TraceWithTimes({0.5, 0.75}), truth); }, path, 0, "poses");
}

TEST(CheckGroundTruthMatches, TimeMismatchNamesTheLine) {
  TempDir dir;
  const std::string path = dir.Write("gt.txt", "# header\n0.5 1 2 3\n0.8 1 2 3\n");
  const GroundTruth truth = ReadGroundTruth(path);
  ExpectInputError([&] { CheckGroundTruthMatches(TraceWithTimes({0.5, 0.75}), truth); }, path, 3, "t");
}

}  // namespace
}  // namespace rc
