#include "maps/movingai_map_loader.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "support/input_error_expectations.h"
#include "support/temp_dir.h"

namespace rc {
namespace {

using test::ThrowsInputError;

const std::string kHeader = "type octile\nheight 3\nwidth 4\nmap\n";

TEST(MovingAiMapLoader, ColumnsAreXAndLinesAreYAsInScenarios) {
  test::TempDir dir;
  const auto path = dir.Write("m.map", kHeader + ".@..\n..T.\nG.SW\n");
  const OccupancyGrid g = LoadMovingAiMap(path);
  ASSERT_EQ(g.size_x(), 4);
  ASSERT_EQ(g.size_y(), 3);
  EXPECT_DOUBLE_EQ(g.resolution_m(), 1.0);
  EXPECT_EQ(g.At(1, 0), CellState::kOccupied);  // '@' on line 0, column 1
  EXPECT_EQ(g.At(2, 1), CellState::kOccupied);  // 'T'
  EXPECT_EQ(g.At(0, 2), CellState::kFree);      // 'G'
  EXPECT_EQ(g.At(2, 2), CellState::kOccupied);  // 'S' swamp is blocked
  EXPECT_EQ(g.At(3, 2), CellState::kOccupied);  // 'W' water is blocked
  EXPECT_EQ(g.CountCells(CellState::kFree), 8u);
  EXPECT_EQ(g.CountCells(CellState::kUnknown), 0u);
}

TEST(MovingAiMapLoader, OutOfBoundsIsBlockedAndResolutionIsAnOption) {
  test::TempDir dir;
  const auto path = dir.Write("m.map", "type octile\nheight 1\nwidth 2\nmap\nO.\n");
  MovingAiMapOptions o;
  o.resolution_m = 0.25;
  const OccupancyGrid g = LoadMovingAiMap(path, o);
  EXPECT_EQ(g.At(0, 0), CellState::kOccupied);
  EXPECT_EQ(g.At(1, 0), CellState::kFree);
  EXPECT_DOUBLE_EQ(g.extent_x_m(), 0.5);
}

TEST(MovingAiMapLoader, AcceptsWindowsLineEndingsAndWidthBeforeHeight) {
  test::TempDir dir;
  const auto path = dir.Write("m.map", "type octile\r\nwidth 2\r\nheight 2\r\nmap\r\n.@\r\n@.\r\n");
  const OccupancyGrid g = LoadMovingAiMap(path);
  EXPECT_EQ(g.At(0, 0), CellState::kFree);
  EXPECT_EQ(g.At(1, 0), CellState::kOccupied);
  EXPECT_EQ(g.At(1, 1), CellState::kFree);
}

// Editors and generators leave spaces or tabs after a row, as they leave
// CRLF; the row's cells are still exactly `width` characters.
TEST(MovingAiMapLoader, AcceptsTrailingSpacesAfterARowAndAByteOrderMark) {
  test::TempDir dir;
  const auto path = dir.Write("m.map", "\xEF\xBB\xBFtype octile\nheight 3\nwidth 4\nmap \n.@.. \n..T.\t\r\nG.SW  \t\n");
  const OccupancyGrid g = LoadMovingAiMap(path);
  EXPECT_EQ(g.At(1, 0), CellState::kOccupied);
  EXPECT_EQ(g.At(2, 1), CellState::kOccupied);
  EXPECT_EQ(g.At(3, 2), CellState::kOccupied);
  EXPECT_EQ(g.CountCells(CellState::kFree), 8u);
}

TEST(MovingAiMapLoader, NonPositiveResolutionIsAUsageError) {
  test::TempDir dir;
  const auto path = dir.Write("m.map", kHeader + "....\n....\n....\n");
  MovingAiMapOptions o;
  o.resolution_m = 0.0;
  EXPECT_THROW(LoadMovingAiMap(path, o), UsageError);
  o.resolution_m = -1.0;
  EXPECT_THROW(LoadMovingAiMap(path, o), UsageError);
}

using test::MalformedCase;

const std::vector<MalformedCase> kMovingAiMalformedCases = {
    MalformedCase{"short_row", kHeader + "....\n...\n....\n", 6, "map row 1", "has 3 characters, expected width 4"},
    MalformedCase{"long_row", kHeader + ".....\n", 5, "map row 0", "has 5 characters"},
    MalformedCase{"space_before_row", kHeader + "....\n ....\n", 6, "map row 1", "has 5"},
    MalformedCase{"tab_inside_row", kHeader + "....\n..\t..\n", 6, "map row 1", "has 5"},
    MalformedCase{"too_few_rows", kHeader + "....\n....\n", 7, "map row 2", "file ends after 2 of 3 rows"},
    MalformedCase{"too_many_rows", kHeader + "....\n....\n....\n....\n", 8, "trailing data",
                  "content after the last of 3 map rows"},
    MalformedCase{"unknown_character", kHeader + "....\n..X.\n....\n", 6, "map row 1, column 2",
                  "unknown terrain character 'X'"},
    MalformedCase{"space_character", kHeader + "....\n. ..\n....\n", 6, "map row 1, column 1", "space"},
    MalformedCase{"missing_type", "height 3\nwidth 4\nmap\n", 3, "type", "missing 'type octile'"},
    MalformedCase{"missing_height", "type octile\nwidth 4\nmap\n", 3, "height", "missing"},
    MalformedCase{"missing_width", "type octile\nheight 3\nmap\n", 3, "width", "missing"},
    MalformedCase{"missing_map_line", "type octile\nheight 3\nwidth 4\n", 4, "map", "file ends before the 'map' line"},
    MalformedCase{"empty_file", "", 1, "map", "file ends before"},
    MalformedCase{"not_a_movingai_map", "mapsize_x 30\n", 1, "header", "unknown header line"},
    MalformedCase{"other_type", "type tile\nheight 3\nwidth 4\nmap\n", 1, "type", "'tile' is not 'octile'"},
    MalformedCase{"duplicate_height", "type octile\nheight 3\nheight 3\n", 3, "height", "appears twice"},
    MalformedCase{"zero_height", "type octile\nheight 0\nwidth 4\nmap\n", 2, "height", "outside [1,"},
    MalformedCase{"negative_width", "type octile\nheight 3\nwidth -4\nmap\n", 3, "width", "outside [1,"},
    MalformedCase{"text_width", "type octile\nheight 3\nwidth four\nmap\n", 3, "width", "not an integer"},
    MalformedCase{"impossible_size", "type octile\nheight 100000\nwidth 100000\nmap\n", 4, "map", "exceeds the limit"},
    MalformedCase{"huge_side", "type octile\nheight 3\nwidth 100001\nmap\n", 3, "width", "outside [1, 100000]"},
    MalformedCase{"map_with_value", "type octile\nheight 3\nwidth 4\nmap 1\n", 4, "map", "'map' alone"}};

TEST(MovingAiMapLoader, ThrowsInputErrorAtLineAndField) {
  test::ExpectEveryCaseRefused(kMovingAiMalformedCases, "bad.map",
                               [](const std::string& path) { LoadMovingAiMap(path); });
}

TEST(MovingAiMapLoader, MissingFileIsAnInputError) {
  EXPECT_TRUE(ThrowsInputError([] { LoadMovingAiMap("/nonexistent/a.map"); }, 0, "", "cannot open"));
}

}  // namespace
}  // namespace rc
