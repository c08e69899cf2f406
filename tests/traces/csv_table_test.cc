#include "traces/csv_table.h"

#include <cmath>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <limits>
#include <stdexcept>

#include <gtest/gtest.h>

#include "support/input_error_expectations.h"
#include "support/temp_dir.h"

namespace rc {
namespace {

using test::ExpectInputError;
using test::TempDir;

TEST(CsvTable, WritesTypedCellsAndReadsThemBack) {
  TempDir dir;
  const std::string path = dir.Path("timeline.csv");
  CsvTable table(path, {"iteration", "time_s", "est_x_m", "backend", "cycles"});
  table.AddRow({0, 0.5, 1.0 / 3.0, "simt", std::uint64_t{18446744073709551615ull}});
  table.AddRow({1, -2.5e-7, CsvCell::Empty(), "tta+, \"cr\"", -3});
  table.AddRow(table.NewRow()
                   .Set("backend", "robo\ncore")
                   .Set("cycles", 7L)
                   .Set("est_x_m", 1e21)
                   .Set("time_s", 1.0f)
                   .Set("iteration", 2u));
  EXPECT_EQ(table.row_count(), 3u);
  EXPECT_EQ(dir.FileCount(), 1);  // only the temporary so far
  table.Commit();

  const CsvContents csv = ReadCsv(path);
  EXPECT_EQ(csv.header, (std::vector<std::string>{"iteration", "time_s", "est_x_m", "backend", "cycles"}));
  ASSERT_EQ(csv.rows.size(), 3u);
  EXPECT_EQ(csv.rows[0], (std::vector<std::string>{"0", "0.5", "0.333333333", "simt", "18446744073709551615"}));
  EXPECT_EQ(csv.rows[1], (std::vector<std::string>{"1", "-2.5e-07", "", "tta+, \"cr\"", "-3"}));
  EXPECT_EQ(csv.rows[2], (std::vector<std::string>{"2", "1", "1e+21", "robo\ncore", "7"}));
  EXPECT_EQ(dir.FileCount(), 1);
}

TEST(CsvTable, SignificantDigitsOption) {
  TempDir dir;
  const std::string path = dir.Path("t.csv");
  CsvTableOptions options;
  options.significant_digits = 17;
  CsvTable table(path, {"time_s"}, options);
  table.AddRow({1234567890.123456});
  table.Commit();
  EXPECT_EQ(std::stod(ReadCsv(path).rows[0][0]), 1234567890.123456);
}

TEST(CsvTable, RejectsNanAndInfCellsNamingColumnAndRow) {
  TempDir dir;
  CsvTable table(dir.Path("t.csv"), {"a_m", "b_m"});
  table.AddRow({1.0, 2.0});
  try {
    table.AddRow({1.0, std::nan("")});
    FAIL() << "NaN accepted";
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("row 2"), std::string::npos) << message;
    EXPECT_NE(message.find("'b_m'"), std::string::npos) << message;
    EXPECT_NE(message.find("NaN"), std::string::npos) << message;
  }
  EXPECT_THROW(table.AddRow({std::numeric_limits<double>::infinity(), 0.0}), std::invalid_argument);
  EXPECT_EQ(table.row_count(), 1u);
}

TEST(CsvTable, RowMustSetEveryColumn) {
  TempDir dir;
  CsvTable table(dir.Path("t.csv"), {"a_m", "b_m"});
  EXPECT_THROW(table.AddRow(table.NewRow().Set("a_m", 1.0)), std::invalid_argument);
  EXPECT_THROW(table.NewRow().Set("c_m", 1.0), std::invalid_argument);
  EXPECT_THROW(table.AddRow({1.0}), std::invalid_argument);
}

TEST(CsvTable, RejectsBadColumnNames) {
  TempDir dir;
  EXPECT_THROW(CsvTable(dir.Path("a.csv"), {"x_m", "x_m"}), std::invalid_argument);
  EXPECT_THROW(CsvTable(dir.Path("b.csv"), {"x,m"}), std::invalid_argument);
  EXPECT_THROW(CsvTable(dir.Path("c.csv"), {""}), std::invalid_argument);
  EXPECT_THROW(CsvTable(dir.Path("d.csv"), {}), std::invalid_argument);
  EXPECT_EQ(dir.FileCount(), 0);
}

TEST(CsvTable, FailedRunLeavesNoFile) {
  TempDir dir;
  {
    CsvTable table(dir.Path("t.csv"), {"a_m"});
    table.AddRow({1.0});
    // destroyed without Commit(), as when a run throws midway
  }
  EXPECT_EQ(dir.FileCount(), 0);
}

TEST(CsvTable, NoRowsAfterCommit) {
  TempDir dir;
  CsvTable table(dir.Path("t.csv"), {"a_m"});
  table.Commit();
  EXPECT_THROW(table.AddRow({1.0}), std::logic_error);
  EXPECT_THROW(table.Commit(), std::logic_error);
  EXPECT_EQ(ReadCsv(dir.Path("t.csv")).rows.size(), 0u);
}

TEST(ReadCsv, CrlfAndQuotedEmptyFields) {
  TempDir dir;
  const CsvContents csv = ReadCsv(dir.Write("t.csv", "a,b\r\n\"\",2\r\n3,\"x\"\"y\"\r\n"));
  ASSERT_EQ(csv.rows.size(), 2u);
  EXPECT_EQ(csv.rows[0], (std::vector<std::string>{"", "2"}));
  EXPECT_EQ(csv.rows[1], (std::vector<std::string>{"3", "x\"y"}));
}

// Spreadsheets save CSV with a UTF-8 byte-order mark; it is not part of the
// first column's name.
TEST(ReadCsv, SkipsAByteOrderMark) {
  TempDir dir;
  const CsvContents csv = ReadCsv(dir.Write("t.csv",
                                            "\xEF\xBB\xBF"
                                            "a,b\n1,2\n"));
  EXPECT_EQ(csv.header, (std::vector<std::string>{"a", "b"}));
  ASSERT_EQ(csv.rows.size(), 1u);
}

TEST(ReadCsvBadInput, ADirectoryIsNotAnEmptyFile) {
  TempDir dir;
  EXPECT_TRUE(test::ThrowsInputError([&] { ReadCsv(dir.path().string()); }, 0, "", "is a directory, not a file"));
}

TEST(ReadCsvBadInput, RowWidthDiffersFromHeader) {
  TempDir dir;
  const std::string path = dir.Write("t.csv", "a,b\n1,2\n3\n");
  ExpectInputError([&] { ReadCsv(path); }, path, 3, "column count");
}

TEST(ReadCsvBadInput, UnterminatedQuote) {
  TempDir dir;
  const std::string path = dir.Write("t.csv", "a,b\n1,\"open\n");
  ExpectInputError([&] { ReadCsv(path); }, path, 2, "column 2");
}

TEST(ReadCsvBadInput, TextAfterClosingQuote) {
  TempDir dir;
  const std::string path = dir.Write("t.csv", "a\n\"x\"y\n");
  ExpectInputError([&] { ReadCsv(path); }, path, 2, "column 1");
}

TEST(ReadCsvBadInput, EmptyFile) {
  TempDir dir;
  const std::string path = dir.Write("t.csv", "");
  ExpectInputError([&] { ReadCsv(path); }, path, 0, "header");
}

// ---- Timeline mode: a marked prefix while the run goes. ----

std::string FileText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

TEST(CsvTimeline, RowsAreInTheFileAsTheyComeUnderTheMarker) {
  TempDir dir;
  const std::string path = dir.Path("out/sub/t.csv");  // folders made on demand
  CsvTableOptions options;
  options.timeline = true;
  CsvTable table(path, {"i", "x_m"}, options);
  table.AddRow({0, 1.5});
  table.AddRow({1, 2.5});
  // Not committed: what a killed run leaves.
  EXPECT_EQ(FileText(path), std::string(kIncompleteMarker) + "\ni,x_m\n0,1.5\n1,2.5\n");
  const CsvContents prefix = ReadCsv(path);
  EXPECT_FALSE(prefix.complete);
  EXPECT_EQ(prefix.header, (std::vector<std::string>{"i", "x_m"}));
  EXPECT_EQ(prefix.rows.size(), 2u);
  table.Commit();
  EXPECT_EQ(FileText(path), "i,x_m\n0,1.5\n1,2.5\n");
  EXPECT_TRUE(ReadCsv(path).complete);
}

TEST(CsvTimeline, HindsightColumnsAreAddedAtCommit) {
  TempDir dir;
  CsvTableOptions options;
  options.timeline = true;
  options.hindsight_columns = {"oracle"};
  CsvTable table(dir.Path("t.csv"), {"i", "note"}, options);
  table.AddRow({0, "a,b"});          // a quoted cell
  table.AddRow({1, "line\nbreak"});  // a quoted newline: rows are found by offset, not by line
  EXPECT_THROW(table.Commit(), std::logic_error);
  table.Commit([](std::size_t row) { return std::vector<CsvCell>{static_cast<int>(10 * row)}; });
  const CsvContents t = ReadCsv(dir.Path("t.csv"));
  EXPECT_EQ(t.header, (std::vector<std::string>{"i", "note", "oracle"}));
  ASSERT_EQ(t.rows.size(), 2u);
  EXPECT_EQ(t.rows[0], (std::vector<std::string>{"0", "a,b", "0"}));
  EXPECT_EQ(t.rows[1], (std::vector<std::string>{"1", "line\nbreak", "10"}));
}

TEST(CsvTimeline, AFailedRunLeavesTheMarkedPrefix) {
  TempDir dir;
  CsvTableOptions options;
  options.timeline = true;
  {
    CsvTable table(dir.Path("t.csv"), {"i"}, options);
    table.AddRow({0});
  }
  EXPECT_FALSE(ReadCsv(dir.Path("t.csv")).complete);
  EXPECT_EQ(ReadCsv(dir.Path("t.csv")).rows.size(), 1u);
}

TEST(ReadCsv, APrefixCutMidRowDropsTheCutRow) {
  TempDir dir;
  const CsvContents t = ReadCsv(dir.Write("t.csv", std::string(kIncompleteMarker) + "\na,b\n1,2\n3,"));
  EXPECT_FALSE(t.complete);
  EXPECT_EQ(t.rows.size(), 1u);
  EXPECT_EQ(t.dropped_partial_rows, 1);
  // Without the marker the same cut is an error: a complete table is never cut.
  EXPECT_THROW(ReadCsv(dir.Write("u.csv", "a,b\n1,2\n3\n")), InputError);
}

}  // namespace
}  // namespace rc
