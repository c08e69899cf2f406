#include "traces/rowild_log_reader.h"

#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "support/input_error_expectations.h"
#include "support/temp_dir.h"
#include "support/test_data.h"
#include "traces/cmu_log_reader.h"

namespace rc {
namespace {

using test::ExpectInputError;
using test::TempDir;

std::vector<std::string> GoodFields() {
  std::vector<std::string> f = {"100.000", "200.000", "0.500"};
  f.resize(183, "300.0");
  return f;
}

std::string RowildLine(const std::vector<std::string>& fields = GoodFields()) {
  std::string line;
  for (std::size_t i = 0; i < fields.size(); ++i) line += (i ? " " : "") + fields[i];
  return line + "\n";
}

TEST(RowildLogReader, ReadsRecordWithZeroTime) {
  TempDir dir;
  auto f = GoodFields();
  f[3] = "66.0";
  f[4] = "0.0";  // a zero reading is valid (see record_fields.h)
  const std::string path = dir.Write("ok.txt", RowildLine(f) + "\n" + RowildLine());
  TraceReadStats stats;
  const SensorTrace trace = ReadRowildLog(path, &stats);
  ASSERT_EQ(trace.scans.size(), 2u);
  EXPECT_EQ(trace.format, "rowild");
  EXPECT_EQ(trace.geometry.beam_count, 180);
  EXPECT_EQ(trace.scans[0].time_s, 0.0);
  EXPECT_EQ(trace.scans[1].time_s, 0.0);
  EXPECT_EQ(trace.scans[1].source_line, 3);  // the blank line 2 is skipped
  EXPECT_DOUBLE_EQ(trace.scans[0].odometry.x, 1.0);
  EXPECT_DOUBLE_EQ(trace.scans[0].odometry.y, 2.0);
  EXPECT_DOUBLE_EQ(trace.scans[0].odometry.theta, 0.5);
  EXPECT_EQ(trace.scans[0].ranges_m[0], 0.66f);
  EXPECT_EQ(trace.scans[0].ranges_m[1], 0.0f);
  EXPECT_EQ(stats.laser_records, 2);
}

TEST(RowildLogReaderBadInput, NanRange) {
  TempDir dir;
  auto f = GoodFields();
  f[3 + 36] = "NaN";
  const std::string path = dir.Write("nan.txt", RowildLine() + RowildLine(f));
  ExpectInputError([&] { ReadRowildLog(path); }, path, 2, "range 37");
}

TEST(RowildLogReaderBadInput, InfRange) {
  TempDir dir;
  auto f = GoodFields();
  f[3 + 99] = "-inf";
  const std::string path = dir.Write("inf.txt", RowildLine(f));
  ExpectInputError([&] { ReadRowildLog(path); }, path, 1, "range 100");
}

TEST(RowildLogReaderBadInput, NegativeRange) {
  TempDir dir;
  auto f = GoodFields();
  f[3] = "-0.5";
  const std::string path = dir.Write("neg.txt", RowildLine(f));
  ExpectInputError([&] { ReadRowildLog(path); }, path, 1, "range 1");
}

TEST(RowildLogReaderBadInput, TruncatedLine) {
  TempDir dir;
  auto f = GoodFields();
  f.resize(2);  // the heading is missing
  const std::string path = dir.Write("cut.txt", RowildLine() + RowildLine() + RowildLine(f));
  ExpectInputError([&] { ReadRowildLog(path); }, path, 3, "theta");
}

TEST(RowildLogReaderBadInput, WrongBeamCount) {
  TempDir dir;
  auto f = GoodFields();
  f.resize(182);  // 179 ranges
  const std::string path = dir.Write("179.txt", RowildLine(f));
  ExpectInputError([&] { ReadRowildLog(path); }, path, 1, "range 180");
  f.resize(184, "300.0");  // 181 ranges
  const std::string longer = dir.Write("181.txt", RowildLine(f));
  ExpectInputError([&] { ReadRowildLog(longer); }, longer, 1, "field 184");
}

TEST(RowildLogReaderBadInput, NonNumericField) {
  TempDir dir;
  auto f = GoodFields();
  f[1] = "2OO.0";
  const std::string path = dir.Write("alpha.txt", RowildLine(f));
  ExpectInputError([&] { ReadRowildLog(path); }, path, 1, "y");
}

TEST(RowildLogReaderBadInput, EmptyTrace) {
  TempDir dir;
  const std::string path = dir.Write("empty.txt", "\n\n");
  ExpectInputError([&] { ReadRowildLog(path); }, path, 0, "laser records");
}

// rowild_log1.txt is robotdata1.log's L records with the laser pose and time
// dropped, the pose rounded to 3 decimals and ranges printed as "66.0".
TEST(RowildRealLog, MatchesRobotdata1LaserRecords) {
  RC_REQUIRE_SHARED_DATA("wean/rowild_log1.txt");
  RC_REQUIRE_SHARED_DATA("wean/robotdata1.log");
  const SensorTrace rowild = ReadRowildLog(test::SharedDataPath("wean/rowild_log1.txt"));
  const SensorTrace cmu = ReadCmuLog(test::SharedDataPath("wean/robotdata1.log"));
  ASSERT_EQ(rowild.scans.size(), 713u);
  ASSERT_EQ(cmu.scans.size(), rowild.scans.size());
  for (std::size_t k = 0; k < cmu.scans.size(); ++k) {
    const LaserScan& a = rowild.scans[k];
    const LaserScan& b = cmu.scans[k];
    EXPECT_EQ(a.source_line, static_cast<long>(k + 1));
    // 3 decimals of cm and rad: half a unit of the last place, plus slack.
    EXPECT_NEAR(a.odometry.x, b.odometry.x, 0.0005 / 100 + 1e-12) << "record " << k;
    EXPECT_NEAR(a.odometry.y, b.odometry.y, 0.0005 / 100 + 1e-12) << "record " << k;
    EXPECT_NEAR(a.odometry.theta, b.odometry.theta, 0.0005 + 1e-12) << "record " << k;
    ASSERT_EQ(a.ranges_m, b.ranges_m) << "record " << k;  // whole cm both ways: identical floats
  }
}

}  // namespace
}  // namespace rc
