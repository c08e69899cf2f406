// Which way round are wean.dat's values? ../shared/data/README.md says the
// data only make sense as P(free); these tests pin that down on the real map.
#include <gtest/gtest.h>

#include <algorithm>

#include "maps/cmu_map_loader.h"
#include "maps/distance_field.h"
#include "support/test_data.h"

namespace rc {
namespace {

// Cells in the middle of Wean Hall's long corridor (x index, y index; 10 cm
// cells), read off a rendering of the map: the corridor runs along x from
// about x = 190 to 510 with its centre near y = 405..415.
const int kCorridorCells[][2] = {{250, 415}, {300, 410}, {350, 405}};

// Largest distance (m) from a free cell to the nearest occupied cell.
float MostOpenFreeCell(const OccupancyGrid& g) {
  const DistanceField field = DistanceField::Build(g, DistanceTarget::kOccupied);
  float best = 0.0f;
  for (int ix = 0; ix < g.size_x(); ++ix)
    for (int iy = 0; iy < g.size_y(); ++iy)
      if (g.At(ix, iy) == CellState::kFree) best = std::max(best, field.At(ix, iy));
  return best;
}

class WeanConvention : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    if (!std::filesystem::exists(test::SharedDataPath("wean/wean.dat"))) return;
    as_free_ = new OccupancyGrid(LoadCmuMap(test::SharedDataPath("wean/wean.dat")));
    CmuMapOptions o;
    o.convention = ValueConvention::kProbabilityOccupied;
    as_occupied_ = new OccupancyGrid(LoadCmuMap(test::SharedDataPath("wean/wean.dat"), o));
  }
  static void TearDownTestSuite() {
    delete as_free_;
    delete as_occupied_;
    as_free_ = as_occupied_ = nullptr;
  }
  static OccupancyGrid* as_free_;
  static OccupancyGrid* as_occupied_;
};
OccupancyGrid* WeanConvention::as_free_ = nullptr;
OccupancyGrid* WeanConvention::as_occupied_ = nullptr;

TEST_F(WeanConvention, DefaultPFreeMakesTheCorridorFreeAndTheHallOpen) {
  RC_REQUIRE_SHARED_DATA("wean/wean.dat");
  const OccupancyGrid& g = *as_free_;
  ASSERT_EQ(g.size_x(), 800);
  ASSERT_EQ(g.size_y(), 800);
  for (const auto& c : kCorridorCells) EXPECT_EQ(g.At(c[0], c[1]), CellState::kFree) << c[0] << "," << c[1];
  // The open areas are metres across (measured: 4.9 m), room for 5 m readings.
  EXPECT_GT(MostOpenFreeCell(g), 3.0f);
}

TEST_F(WeanConvention, PoccupiedPutsWallsInTheCorridorAndNoOpenSpaceRemains) {
  RC_REQUIRE_SHARED_DATA("wean/wean.dat");
  const OccupancyGrid& g = *as_occupied_;
  for (const auto& c : kCorridorCells) EXPECT_EQ(g.At(c[0], c[1]), CellState::kOccupied) << c[0] << "," << c[1];
  // The "free" space is now the walls: nowhere is more than about a metre
  // from an obstacle (measured: 1.3 m).
  EXPECT_LT(MostOpenFreeCell(g), 1.5f);
  // Wean Hall's walls are thin, so reading them as floor leaves far fewer
  // free cells (measured: 48332 as P(free), 18019 as P(occupied)).
  EXPECT_GT(as_free_->CountCells(CellState::kFree), 2 * g.CountCells(CellState::kFree));
}

// The map line's cell classes: most of what wean.dat observed lies between
// ROS's thresholds (the unexplored halo, ../shared/data/README.md), which a
// user now sees, and can move with --occupied-thresh / --free-thresh.
TEST(WeanCellClasses, MostObservedCellsLieBetweenTheThresholds) {
  RC_REQUIRE_SHARED_DATA("wean/wean.dat");
  CellClassCounts counts;
  LoadCmuMap(test::SharedDataPath("wean/wean.dat"), {}, &counts);
  EXPECT_EQ(counts.Total(), 640000u);
  EXPECT_EQ(counts.Of(CellClass::kFree), 48332u);
  EXPECT_EQ(counts.Of(CellClass::kOccupied), 20224u);
  EXPECT_EQ(counts.Of(CellClass::kBetweenThresholds), 105301u);
  EXPECT_EQ(counts.Of(CellClass::kUnobserved), 466143u);
  EXPECT_NE(counts.Describe().find("60.6% of observed"), std::string::npos) << counts.Describe();
  // A free threshold above the halo's P(occupied) 0.20-0.35 turns it free.
  CmuMapOptions wide;
  wide.thresholds.free_thresh = 0.36;
  CellClassCounts widened;
  LoadCmuMap(test::SharedDataPath("wean/wean.dat"), wide, &widened);
  EXPECT_GT(widened.Of(CellClass::kFree), counts.Of(CellClass::kFree) + counts.Of(CellClass::kBetweenThresholds) / 2);
}

}  // namespace
}  // namespace rc
