// The real MovingAI benchmark maps and the Intel lab map must load, with
// cell counts that match the files and scenario endpoints on free cells
// (which also checks the x = column, y = line orientation).
#include <gtest/gtest.h>

#include <cctype>
#include <fstream>
#include <sstream>

#include "maps/map_loader.h"
#include "maps/movingai_map_loader.h"
#include "support/test_data.h"

namespace rc {
namespace {

// Passable characters in the map body, counted straight from the file.
std::size_t CountPassable(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  for (int i = 0; i < 4; ++i) std::getline(in, line);  // type, height, width, map
  std::size_t passable = 0;
  while (std::getline(in, line))
    for (char c : line) passable += (c == '.' || c == 'G');
  return passable;
}

class RealMovingAiMap : public ::testing::TestWithParam<const char*> {};

TEST_P(RealMovingAiMap, LoadsWithScenarioEndpointsOnFreeCells) {
  const std::string name = GetParam();
  RC_REQUIRE_SHARED_DATA("movingai/" + name + ".map");
  const std::string path = test::SharedDataPath("movingai/" + name + ".map");
  const LoadedMap map = LoadMap(path);
  EXPECT_EQ(map.format, "movingai");
  const OccupancyGrid& g = map.grid;
  EXPECT_EQ(g.CountCells(CellState::kFree), CountPassable(path));
  EXPECT_EQ(g.CountCells(CellState::kFree) + g.CountCells(CellState::kOccupied), g.cell_count());

  std::ifstream scen(path + ".scen");
  ASSERT_TRUE(scen) << "missing scenario file";
  std::string line;
  std::getline(scen, line);  // version 1
  int checked = 0;
  while (std::getline(scen, line)) {
    std::istringstream fields(line);
    int bucket, width, height, sx, sy, gx, gy;
    std::string map_name;
    if (!(fields >> bucket >> map_name >> width >> height >> sx >> sy >> gx >> gy)) continue;
    ASSERT_EQ(width, g.size_x());
    ASSERT_EQ(height, g.size_y());
    ASSERT_TRUE(g.IsFree(sx, sy)) << line;
    ASSERT_TRUE(g.IsFree(gx, gy)) << line;
    ++checked;
  }
  EXPECT_GT(checked, 10);
}

INSTANTIATE_TEST_SUITE_P(Maps, RealMovingAiMap,
                         ::testing::Values("Boston_0_256", "den312d", "64room_005", "maze512-32-9"),
                         [](const auto& info) {
                           std::string n = info.param;
                           for (char& c : n)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return n;
                         });

TEST(RealMaps, IntelLabMapLoads) {
  RC_REQUIRE_SHARED_DATA("intel/Intel.map");
  const std::string path = test::SharedDataPath("intel/Intel.map");
  const OccupancyGrid g = LoadMovingAiMap(path);
  EXPECT_EQ(g.size_x(), 444);
  EXPECT_EQ(g.size_y(), 292);
  EXPECT_EQ(g.CountCells(CellState::kFree), CountPassable(path));
  EXPECT_GT(g.CountCells(CellState::kOccupied), 0u);
}

}  // namespace
}  // namespace rc
