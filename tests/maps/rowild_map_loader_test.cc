#include "maps/rowild_map_loader.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include "maps/cmu_map_loader.h"
#include "support/input_error_expectations.h"
#include "support/temp_dir.h"
#include "support/test_data.h"

namespace rc {
namespace {

using test::ThrowsInputError;

// 3 cells along x (lines) by 2 along y (columns), 10 cm cells.
const char kSmallHeader[] = "mapsize_x 30\nmapsize_y 20\nresolution 10\n";
const char kSmallRows[] = "1.0 0.0\n-1 0.5\n0.9 0.1\n";

TEST(RowildMapLoader, ReadsLinesAsXAndColumnsAsYUnderPFree) {
  test::TempDir dir;
  const auto path = dir.Write("small.dat", std::string(kSmallHeader) + kSmallRows);
  const OccupancyGrid g = LoadRowildMap(path);
  ASSERT_EQ(g.size_x(), 3);
  ASSERT_EQ(g.size_y(), 2);
  EXPECT_DOUBLE_EQ(g.resolution_m(), 0.1);
  EXPECT_EQ(g.At(0, 0), CellState::kFree);      // 1.0 = surely free
  EXPECT_EQ(g.At(0, 1), CellState::kOccupied);  // 0.0
  EXPECT_EQ(g.At(1, 0), CellState::kUnknown);   // -1
  EXPECT_EQ(g.At(1, 1), CellState::kUnknown);   // 0.5 between the thresholds
  EXPECT_EQ(g.At(2, 0), CellState::kFree);
  EXPECT_EQ(g.At(2, 1), CellState::kOccupied);
}

TEST(RowildMapLoader, POccupiedConventionInvertsKnownCells) {
  test::TempDir dir;
  const auto path = dir.Write("small.dat", std::string(kSmallHeader) + kSmallRows);
  RowildMapOptions o;
  o.convention = ValueConvention::kProbabilityOccupied;
  const OccupancyGrid g = LoadRowildMap(path, o);
  EXPECT_EQ(g.At(0, 0), CellState::kOccupied);
  EXPECT_EQ(g.At(0, 1), CellState::kFree);
  EXPECT_EQ(g.At(1, 0), CellState::kUnknown);
  EXPECT_EQ(g.At(2, 1), CellState::kFree);
}

TEST(RowildMapLoader, BlankLinesInsideTheHeaderAreAccepted) {
  // RoWild's stream extraction skips them too.
  test::TempDir dir;
  const auto path = dir.Write("blank.dat", std::string("\nmapsize_x 30\n\nmapsize_y 20\nresolution 10\n") + kSmallRows);
  EXPECT_EQ(LoadRowildMap(path).size_x(), 3);
}

using test::MalformedCase;

const std::string kHeader = kSmallHeader;

const std::vector<MalformedCase> kRowildMalformedCases = {
    MalformedCase{"truncated", kHeader + "1 0\n0 1\n", 6, "map row 2", "file ends after 2 of 3 rows"},
    MalformedCase{"empty_file", "", 1, "mapsize_x", "file ends before"},
    MalformedCase{"header_only", kHeader, 4, "map row 0", "file ends after 0 of 3 rows"},
    MalformedCase{"short_row", kHeader + "1 0\n0\n1 1\n", 5, "map row 1", "has 1 values, expected 2"},
    MalformedCase{"long_row", kHeader + "1 0 1\n", 4, "map row 0", "has 3 values, expected 2"},
    MalformedCase{"blank_line_before_rows", kHeader + "\n1 0\n0 1\n1 1\n", 4, "map row 0", "has 0 values"},
    MalformedCase{"nan_value", kHeader + "1 nan\n0 1\n1 1\n", 4, "map row 0, column 1", "not finite"},
    MalformedCase{"text_value", kHeader + "1 0\n0 x\n1 1\n", 5, "map row 1, column 1", "not a number"},
    MalformedCase{"value_above_one", kHeader + "1 0\n0 1.5\n1 1\n", 5, "map row 1, column 1", "neither a probability"},
    MalformedCase{"value_minus_half", kHeader + "1 0\n0 1\n-0.5 1\n", 6, "map row 2, column 0",
                  "neither a probability"},
    MalformedCase{"wrong_key_order", "mapsize_y 20\nmapsize_x 30\nresolution 10\n", 1, "mapsize_x",
                  "expected 'mapsize_x"},
    MalformedCase{"cmu_header", "robot_specifications->resolution 10\n", 1, "mapsize_x",
                  "found 'robot_specifications->resolution'"},
    MalformedCase{"missing_value", "mapsize_x\n", 1, "mapsize_x", "exactly one integer"},
    MalformedCase{"fractional_resolution", "mapsize_x 30\nmapsize_y 20\nresolution 10.5\n", 3, "resolution",
                  "not an integer"},
    MalformedCase{"zero_resolution", "mapsize_x 30\nmapsize_y 20\nresolution 0\n", 3, "resolution", "outside [1,"},
    MalformedCase{"negative_resolution", "mapsize_x 30\nmapsize_y 20\nresolution -10\n", 3, "resolution",
                  "outside [1,"},
    MalformedCase{"zero_extent", "mapsize_x 0\nmapsize_y 20\nresolution 10\n", 1, "mapsize_x", "outside [1,"},
    MalformedCase{"partial_cell", "mapsize_x 35\nmapsize_y 20\nresolution 10\n", 1, "mapsize_x",
                  "not a whole number of 10 cm cells"},
    MalformedCase{"impossible_size", "mapsize_x 9000000\nmapsize_y 20\nresolution 1\n", 1, "mapsize_x", "impossible"},
    MalformedCase{"too_many_cells", "mapsize_x 5000000\nmapsize_y 5000000\nresolution 100\n", 1, "mapsize_x",
                  "exceeds the limit"},
    MalformedCase{"trailing_data", kHeader + kSmallRows + "\n0 0\n", 8, "trailing data", "extra content"}};

TEST(RowildMapLoader, ThrowsInputErrorAtLineAndField) {
  test::ExpectEveryCaseRefused(kRowildMalformedCases, "bad.dat", [](const std::string& path) { LoadRowildMap(path); });
}

TEST(RowildMapLoader, MissingFileIsAnInputErrorForTheWholeFile) {
  EXPECT_TRUE(ThrowsInputError([] { LoadRowildMap("/nonexistent/map.dat"); }, 0, "", "cannot open"));
}

// wean.dat rewritten with RoWild's header must give the very same grid.
TEST(RowildMapLoader, WeanInRowildFormatMatchesTheCmuLoader) {
  RC_REQUIRE_SHARED_DATA("wean/wean.dat");
  test::TempDir dir;
  const std::string rowild_path = dir.Path("wean_rowild.dat");
  {
    std::ifstream in(test::SharedDataPath("wean/wean.dat"));
    std::ofstream out(rowild_path);
    out << "mapsize_x 8000\nmapsize_y 8000\nresolution 10\n";
    std::string line;
    bool in_rows = false;
    while (std::getline(in, line)) {
      if (in_rows) out << line << '\n';
      if (line.rfind("global_map[0]:", 0) == 0) in_rows = true;
    }
  }
  const OccupancyGrid cmu = LoadCmuMap(test::SharedDataPath("wean/wean.dat"));
  const OccupancyGrid rowild = LoadRowildMap(rowild_path);
  ASSERT_EQ(rowild.size_x(), cmu.size_x());
  ASSERT_EQ(rowild.size_y(), cmu.size_y());
  EXPECT_DOUBLE_EQ(rowild.resolution_m(), cmu.resolution_m());
  EXPECT_TRUE(rowild.cells() == cmu.cells());
}

}  // namespace
}  // namespace rc
