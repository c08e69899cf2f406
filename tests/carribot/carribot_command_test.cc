// `rcbench carribot` end to end, in process: the command is registered on a
// fresh CLI11 app and run like main() does, mapping exceptions to exit codes
// with common/exit_codes.h (1 InputError, 2 UsageError and CLI11 parse errors). Exit code 3 leaves
// through std::exit, so those cases are death tests (the child process writes
// its outputs before exiting; the parent then reads them).
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <iterator>

#include <CLI/CLI.hpp>
#include <opencv2/imgcodecs.hpp>

#include "common/exit_codes.h"

#include "common/input_error.h"
#include "support/temp_dir.h"
#include "support/test_data.h"
#include "traces/csv_table.h"
#include "workloads/rcbench/commands.h"

namespace rc {
namespace {

// Runs `rcbench carribot ARGS...`; returns main()'s exit code.
int RunCarribot(std::vector<std::string> args) {
  CLI::App app{"rcbench"};
  app.require_subcommand(1);
  AddCarribotCommand(app);
  args.insert(args.begin(), {"rcbench", "carribot", "--quiet"});
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  try {
    app.parse(static_cast<int>(argv.size()), argv.data());
  } catch (const CLI::ParseError&) {
    return ToInt(ExitCode::kUsage);
  } catch (...) {
    return ToInt(ReportException(std::current_exception(), std::cerr));  // main()'s table
  }
  return 0;
}

// The cell of `row` in the column named `name`.
std::string Cell(const CsvContents& t, std::size_t row, const std::string& name) {
  const auto it = std::find(t.header.begin(), t.header.end(), name);
  if (it == t.header.end()) throw std::invalid_argument("no column " + name);
  return t.rows.at(row).at(static_cast<std::size_t>(it - t.header.begin()));
}

const std::string kRoomsMap = "type octile\nheight 3\nwidth 9\nmap\n....@....\n....@....\n....@....\n";

TEST(CarribotCommand, AllScenariosOfAMapMatchTheirOptima) {
  RC_REQUIRE_SHARED_DATA("movingai/den312d.map");
  test::TempDir dir;
  const std::string map = test::SharedDataPath("movingai/den312d.map");
  ASSERT_EQ(RunCarribot({"--map", map, "--scen", map + ".scen", "--timeline", dir.Path("t.csv")}), 0);
  const CsvContents t = ReadCsv(dir.Path("t.csv"));
  ASSERT_EQ(t.rows.size(), 290u);
  std::string header;
  for (const std::string& column : t.header) header += (header.empty() ? "" : ",") + column;
  // A point robot runs no kernel: no pricing columns.
  ASSERT_EQ(header,
            "scenario,bucket,sx,sy,gx,gy,path_length_cells,path_length_m,optimal_length_cells,turns,expanded,collision_"
            "queries,kernel_launches,kernel_queries,nodes_per_query,wall_s,status");
  for (const auto& row : t.rows) {
    EXPECT_EQ(row[16], "found");
    EXPECT_EQ(row[13], "0");
    EXPECT_NEAR(std::stod(row[6]), std::stod(row[8]), 1e-4) << "scenario " << row[0];
    EXPECT_EQ(row[6], row[7]);  // 1 m per cell
  }
}

TEST(CarribotCommand, SingleFootprintQueryWritesPathAndPlot) {
  RC_REQUIRE_SHARED_DATA("movingai/den312d.map");
  test::TempDir dir;
  const std::string map = test::SharedDataPath("movingai/den312d.map");
  ASSERT_EQ(RunCarribot({"--map", map, "--scen", map + ".scen", "--scenario", "202", "--footprint", "0.5x1.5",
                         "--headings", "16", "--resolution", "0.5", "--path", dir.Path("out/p.csv"), "--plot",
                         dir.Path("out/p.png"), "--timeline", dir.Path("out/t.csv")}),
            0);
  const CsvContents path = ReadCsv(dir.Path("out/p.csv"));
  ASSERT_GE(path.rows.size(), 2u);
  EXPECT_EQ(path.header.front(), "step");
  const CsvContents timeline = ReadCsv(dir.Path("out/t.csv"));
  // The kernel filled the configuration space (the set-up row), then the query.
  ASSERT_EQ(timeline.rows.size(), 2u);
  EXPECT_EQ(Cell(timeline, 0, "status"), "setup");
  EXPECT_EQ(Cell(timeline, 0, "kernel_queries"), std::to_string(65 * 81 * 16));
  EXPECT_EQ(Cell(timeline, 1, "scenario"), "202");
  EXPECT_EQ(Cell(timeline, 1, "kernel_queries"), "0");
  // The last path row's cost is the timeline's path length, in cells and m.
  EXPECT_EQ(path.rows.back()[7], Cell(timeline, 1, "path_length_cells"));
  EXPECT_EQ(path.rows.back()[8], Cell(timeline, 1, "path_length_m"));
  EXPECT_NEAR(std::stod(path.rows.back()[8]), 0.5 * std::stod(Cell(timeline, 1, "path_length_cells")), 1e-6);
  const cv::Mat png = cv::imread(dir.Path("out/p.png"));
  ASSERT_FALSE(png.empty());
  EXPECT_EQ(png.cols, 65 * 7);  // den312d is 65 x 81 cells, magnified to >= 512 px
  EXPECT_EQ(png.rows, 81 * 7);
}

TEST(CarribotCommand, UnreachableGoalExitsWithThreeAndStillWritesTheTimeline) {
  test::TempDir dir;
  const std::string map = dir.Write("rooms.map", kRoomsMap);
  const std::string timeline = dir.Path("t.csv");
  EXPECT_EXIT(RunCarribot({"--map", map, "--start", "0,0", "--goal", "8,2", "--timeline", timeline}),
              ::testing::ExitedWithCode(3), "");
  const CsvContents t = ReadCsv(timeline);
  ASSERT_EQ(t.rows.size(), 1u);
  EXPECT_EQ(Cell(t, 0, "status"), "no_path");
  EXPECT_EQ(Cell(t, 0, "path_length_cells"), "");  // no length for a path that does not exist
  EXPECT_EXIT(RunCarribot({"--map", map, "--start", "4,0", "--goal", "8,2"}), ::testing::ExitedWithCode(3), "");
}

// Every --backend value plans the same path; the timeline prices every
// per-expansion launch on every backend, and adaptive names its choice.
TEST(CarribotCommand, EveryBackendPlansTheSamePathAndPricesEveryLaunch) {
  test::TempDir dir;
  const std::string map = dir.Write("open.map",
                                    "type octile\nheight 6\nwidth 10\nmap\n"
                                    "..........\n..........\n....@.....\n....@.....\n"
                                    "..........\n..........\n");
  std::string first_path;
  for (const std::string backend : {"adaptive", "oracle", "static:simt", "static:ttaplus", "static:ttaplus-p",
                                    "static:ttaplus-cr", "static:robocore"}) {
    const std::string path = dir.Path(backend + "_p.csv"), timeline = dir.Path(backend + "_t.csv");
    ASSERT_EQ(
        RunCarribot({"--map", map, "--start", "1,1", "--goal", "8,4", "--footprint", "0.6x1.2", "--collision-mode",
                     "per-expansion", "--backend", backend, "--path", path, "--timeline", timeline}),
        0)
        << backend;
    std::ifstream in(path);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (first_path.empty()) first_path = text;
    EXPECT_EQ(text, first_path) << backend;
    const CsvContents t = ReadCsv(timeline);
    ASSERT_EQ(t.rows.size(), 1u);
    EXPECT_GT(std::stoll(Cell(t, 0, "kernel_launches")), 1);
    EXPECT_GT(std::stod(Cell(t, 0, "nodes_per_query")), 1.0);
    for (const char* b : {"simt", "ttaplus", "ttaplus_p", "ttaplus_cr", "robocore"})
      EXPECT_GT(std::stod(Cell(t, 0, std::string("cycles_") + b)), 0.0) << b;
    EXPECT_GT(std::stod(Cell(t, 0, "energy_j")), 0.0);
    if (backend.rfind("static:", 0) == 0) {
      EXPECT_EQ("static:" + Cell(t, 0, "backend"), backend);
    }
  }
  EXPECT_EQ(
      RunCarribot({"--map", map, "--start", "1,1", "--goal", "8,4", "--footprint", "0.6x1.2", "--backend", "gpu"}), 2);
}

// --offset moves start and goal by cells of the scaled map, after the
// --map-scale multiplication: at scale 2, start 1,1 with offset 1,0 is cell
// (3, 2), a cell no start X,Y can name (every scaled start is even).
TEST(CarribotCommand, OffsetMovesStartAndGoalInScaledCells) {
  test::TempDir dir;
  const std::string map = dir.Write("open.map",
                                    "type octile\nheight 4\nwidth 6\nmap\n"
                                    "......\n......\n......\n......\n");
  const std::string timeline = dir.Path("t.csv");
  ASSERT_EQ(RunCarribot({"--map", map, "--map-scale", "2", "--start", "1,1", "--goal", "4,2", "--offset", "1,0",
                         "--timeline", timeline}),
            0);
  const CsvContents t = ReadCsv(timeline);
  ASSERT_EQ(t.rows.size(), 1u);
  EXPECT_EQ(Cell(t, 0, "sx"), "3");
  EXPECT_EQ(Cell(t, 0, "sy"), "2");
  EXPECT_EQ(Cell(t, 0, "gx"), "9");
  EXPECT_EQ(Cell(t, 0, "gy"), "4");
  // Outside the 12 x 8 scaled map after the offset, and --offset without --start.
  EXPECT_EQ(RunCarribot({"--map", map, "--map-scale", "2", "--start", "1,1", "--goal", "5,3", "--offset", "2,0"}), 2);
  EXPECT_EQ(RunCarribot({"--map", map, "--start", "1,1", "--goal", "4,2", "--offset", "-2,0"}), 2);
  EXPECT_EQ(RunCarribot({"--map", map, "--offset", "1,0"}), 2);
}

TEST(CarribotCommand, UsageErrorsExitWithTwo) {
  RC_REQUIRE_SHARED_DATA("movingai/den312d.map");
  test::TempDir dir;
  const std::string map = dir.Write("rooms.map", kRoomsMap);
  const std::string den = test::SharedDataPath("movingai/den312d.map");
  const std::string scen = den + ".scen";
  const std::vector<std::vector<std::string>> cases = {
      {"--map", map},                                                        // neither --scen nor --start/--goal
      {"--map", map, "--start", "0,0"},                                      // --start without --goal
      {"--map", den, "--scen", scen, "--start", "1,1", "--goal", "2,2"},     // both
      {"--map", map, "--start", "9,0", "--goal", "0,0"},                     // outside the map
      {"--map", map, "--start", "0,0", "--goal", "1,1", "--headings", "8"},  // --headings needs --footprint
      {"--map", map, "--start", "0,0", "--goal", "1,1", "--footprint", "1by2"},
      {"--map", map, "--start", "0,0", "--goal", "1,1", "--footprint", "1x2", "--headings", "12"},
      {"--map", map, "--start", "0,0", "--goal", "1,1", "--footprint", "1x2", "--start-heading", "8"},
      {"--map", map, "--start", "0,0", "--goal", "1,1", "--weight", "0.5"},
      {"--map", den, "--scen", scen, "--path", dir.Path("p.csv")},  // a path needs one query
      {"--map", den, "--scen", scen, "--scenario", "290"},          // only 290 scenarios
  };
  for (const auto& args : cases) {
    std::string joined;
    for (const auto& a : args) joined += a + " ";
    EXPECT_EQ(RunCarribot(args), 2) << joined;
  }
}

TEST(CarribotCommand, BadInputExitsWithOne) {
  test::TempDir dir;
  const std::string map = dir.Write("rooms.map", kRoomsMap);
  const std::string walls = dir.Write("walls.map", "type octile\nheight 1\nwidth 2\nmap\n@@\n");
  const std::string wrong_size = dir.Write("w.scen", "version 1\n0\trooms.map\t8\t3\t0\t0\t1\t1\t1.41421356\n");
  const std::string truncated = dir.Write("t.scen", "version 1\n0\trooms.map\t9\t3\t0\t0\t1\n");
  EXPECT_EQ(RunCarribot({"--map", walls, "--start", "0,0", "--goal", "1,0"}), 1);  // no free cell
  EXPECT_EQ(RunCarribot({"--map", map, "--scen", wrong_size}), 1);
  EXPECT_EQ(RunCarribot({"--map", map, "--scen", truncated}), 1);
  EXPECT_EQ(RunCarribot({"--map", dir.Path("missing.map"), "--start", "0,0", "--goal", "1,0"}), 1);
}

}  // namespace
}  // namespace rc
