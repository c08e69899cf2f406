// The .scen reader: well-formed files and every malformed line it must name.
#include "workloads/carribot/movingai_scenario_reader.h"

#include <filesystem>

#include <gtest/gtest.h>

#include "carribot/carribot_test_util.h"
#include "support/input_error_expectations.h"
#include "support/temp_dir.h"

namespace rc {
namespace {

using test::ThrowsInputError;

const std::string kGood =
    "version 1\n"
    "0\tm.map\t4\t3\t0\t0\t3\t2\t3.82842712\n"
    "1\tm.map\t4\t3\t3\t2\t0\t0\t3.82842712\r\n"
    "\n";

TEST(MovingAiScenarioReader, ReadsFieldsAndLineNumbers) {
  test::TempDir dir;
  const MovingAiScenarioFile f = ReadMovingAiScenarios(dir.Write("a.scen", kGood));
  ASSERT_EQ(f.scenarios.size(), 2u);
  const MovingAiScenario& s = f.scenarios[1];
  EXPECT_EQ(s.line, 3);
  EXPECT_EQ(s.bucket, 1);
  EXPECT_EQ(s.map_name, "m.map");
  EXPECT_EQ(s.map_width, 4);
  EXPECT_EQ(s.map_height, 3);
  EXPECT_EQ(s.start_x, 3);
  EXPECT_EQ(s.start_y, 2);
  EXPECT_EQ(s.goal_x, 0);
  EXPECT_EQ(s.goal_y, 0);
  EXPECT_DOUBLE_EQ(s.optimal_length, 3.82842712);
}

TEST(MovingAiScenarioReader, VersionLineIsRequired) {
  test::TempDir dir;
  EXPECT_TRUE(ThrowsInputError([&] { ReadMovingAiScenarios(dir.Write("a.scen", "")); }, 1, "version", "empty"));
  EXPECT_TRUE(ThrowsInputError([&] { ReadMovingAiScenarios(dir.Write("b.scen", "version 2\n")); }, 1, "version",
                               "not supported"));
  EXPECT_TRUE(ThrowsInputError([&] { ReadMovingAiScenarios(dir.Write("c.scen", "0\tm.map\t4\t3\t0\t0\t3\t2\t1\n")); },
                               1, "version", "expected 'version 1'"));
}

struct BadLine {
  std::string line;
  std::string field;
  std::string problem;
};

TEST(MovingAiScenarioReader, EveryMalformedLineNamesLineAndField) {
  const std::vector<BadLine> cases = {
      {"0\tm.map\t4\t3\t0\t0\t3", "goal_y", "7 of 9 fields"},
      {"0\tm.map\t4\t3\t0\t0\t3\t2", "optimal_length", "8 of 9"},
      {"0 m.map 4 3 0 0 3 2 1.0", "map", "tabs, not spaces"},
      {"0\tm.map\t4\t3\t0\t0\t3\t2\t1\textra", "optimal_length", "10 fields"},
      {"zero\tm.map\t4\t3\t0\t0\t3\t2\t1", "bucket", "not an integer"},
      {"0\t\t4\t3\t0\t0\t3\t2\t1", "map", "empty map name"},
      {"0\tm.map\tfour\t3\t0\t0\t3\t2\t1", "width", "not an integer"},
      {"0\tm.map\t4\t0\t0\t0\t3\t2\t1", "height", "outside"},
      {"0\tm.map\t4\t3\t4\t0\t3\t2\t1", "start_x", "outside [0, 3]"},
      {"0\tm.map\t4\t3\t0\t-1\t3\t2\t1", "start_y", "outside"},
      {"0\tm.map\t4\t3\t0\t0\t3.5\t2\t1", "goal_x", "not an integer"},
      {"0\tm.map\t4\t3\t0\t0\t3\t3\t1", "goal_y", "outside [0, 2]"},
      {"0\tm.map\t4\t3\t0\t0\t3\t2\tabc", "optimal_length", "not a number"},
      {"0\tm.map\t4\t3\t0\t0\t3\t2\t-1", "optimal_length", "negative"},
      {"0\tm.map\t4\t3\t0\t0\t3\t2\tnan", "optimal_length", "not finite"},
      {"0\tm.map\t4\t3\t0\t0\t3\t2\t0x1p2", "optimal_length", "hexadecimal"},
  };
  test::TempDir dir;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const std::string path = dir.Write("bad" + std::to_string(i) + ".scen",
                                       "version 1\n0\tm.map\t4\t3\t0\t0\t3\t2\t1\n" + cases[i].line + "\n");
    EXPECT_TRUE(ThrowsInputError([&] { ReadMovingAiScenarios(path); }, 3, cases[i].field, cases[i].problem))
        << "case " << i << ": " << cases[i].line;
  }
}

TEST(MovingAiScenarioReader, AByteOrderMarkBeforeTheVersionLineIsSkipped) {
  test::TempDir dir;
  const MovingAiScenarioFile f = ReadMovingAiScenarios(dir.Write("a.scen", "\xEF\xBB\xBF" + kGood));
  ASSERT_EQ(f.scenarios.size(), 2u);
  EXPECT_EQ(f.scenarios[0].line, 2);
}

TEST(MovingAiScenarioReader, ADirectoryIsNotAnEmptyFile) {
  test::TempDir dir;
  const std::string path = dir.Path("a.scen");
  std::filesystem::create_directory(path);
  EXPECT_TRUE(ThrowsInputError([&] { ReadMovingAiScenarios(path); }, 0, "", "is a directory, not a file"));
}

TEST(MovingAiScenarioReader, MissingFileIsAnInputError) {
  EXPECT_TRUE(ThrowsInputError([] { ReadMovingAiScenarios("/nonexistent/x.scen"); }, 0, "", "cannot open"));
}

TEST(MovingAiScenarioReader, MapSizeMustMatchTheGrid) {
  test::TempDir dir;
  const MovingAiScenarioFile f = ReadMovingAiScenarios(dir.Write("a.scen", kGood));
  EXPECT_NO_THROW(CheckScenariosMatchMap(f, OccupancyGrid(4, 3, 1.0)));
  EXPECT_TRUE(ThrowsInputError([&] { CheckScenariosMatchMap(f, OccupancyGrid(5, 3, 1.0)); }, 2, "width",
                               "differs from the map's 5 columns"));
  EXPECT_TRUE(ThrowsInputError([&] { CheckScenariosMatchMap(f, OccupancyGrid(4, 2, 1.0)); }, 2, "height",
                               "differs from the map's 2 lines"));
}

}  // namespace
}  // namespace rc
