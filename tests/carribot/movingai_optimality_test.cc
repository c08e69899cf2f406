// Point-robot A* against the MovingAI benchmark: the path cost must equal the
// published optimal length (cost 1 straight, sqrt(2) diagonal, no corner
// cutting) on every scenario of den312d, Boston_0_256 and 64room_005, and of
// every 4th bucket of maze512-32-9 (2000 of its 8000 scenarios; a maze makes
// A* expand nearly every free cell, so the whole file takes minutes on 2
// cores). Set RC_MOVINGAI_ALL_BUCKETS=1 to check all of maze512 as well.
// A sanitizer build checks every 40th maze512 bucket and every 10th
// 64room_005 bucket (about 200 scenarios each; tests/support/sanitizer_build.h).
// The Intel map has no .scen file: there A* is compared with an independent
// Dijkstra on a few queries.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <mutex>
#include <queue>
#include <thread>

#include <array>
#include <filesystem>
#include <random>

#include "maps/movingai_map_loader.h"
#include "support/sanitizer_build.h"
#include "support/test_data.h"
#include "workloads/carribot/grid_planner.h"
#include "workloads/carribot/movingai_scenario_reader.h"

namespace rc {
namespace {

constexpr double kLengthTolerance = 1e-4;  // the .scen files print 8 decimals

struct Mismatch {
  std::size_t index;
  std::string what;
};

// Plans every scenario (two worker threads, one planner each: a planner's
// search arrays are not shared) and returns the mismatches in scenario order.
std::vector<Mismatch> PlanAll(const OccupancyGrid& grid, const std::vector<MovingAiScenario>& scenarios) {
  std::vector<Mismatch> mismatches;
  std::mutex mutex;
  std::atomic<std::size_t> next{0};
  const auto worker = [&] {
    auto planner = GridPlanner::Create(grid, PlannerOptions{});
    for (std::size_t i = next++; i < scenarios.size(); i = next++) {
      const MovingAiScenario& s = scenarios[i];
      const PlanResult r = planner->Plan({s.start_x, s.start_y}, {s.goal_x, s.goal_y});
      std::string what;
      if (!r.found())
        what = std::string("status ") + ToString(r.status) + ": " + r.message;
      else if (std::abs(r.length_cells - s.optimal_length) > kLengthTolerance)
        what = "length " + std::to_string(r.length_cells) + " vs optimal " + std::to_string(s.optimal_length);
      if (!what.empty()) {
        std::lock_guard<std::mutex> lock(mutex);
        mismatches.push_back({i, "line " + std::to_string(s.line) + ": " + what});
      }
    }
  };
  std::thread a(worker), b(worker);
  a.join();
  b.join();
  std::sort(mismatches.begin(), mismatches.end(),
            [](const Mismatch& x, const Mismatch& y) { return x.index < y.index; });
  return mismatches;
}

// bucket_stride 1: every scenario; k: the scenarios of every k-th bucket.
void ExpectScenariosOptimal(const std::string& map_name, int bucket_stride = 1) {
  const std::string map_path = test::SharedDataPath("movingai/" + map_name);
  const OccupancyGrid grid = LoadMovingAiMap(map_path);
  const MovingAiScenarioFile file = ReadMovingAiScenarios(map_path + ".scen");
  CheckScenariosMatchMap(file, grid);
  std::vector<MovingAiScenario> chosen;
  for (const MovingAiScenario& s : file.scenarios)
    if (s.bucket % bucket_stride == 0) chosen.push_back(s);
  ASSERT_GT(chosen.size(), 100u);
  const std::vector<Mismatch> mismatches = PlanAll(grid, chosen);
  EXPECT_TRUE(mismatches.empty()) << mismatches.size() << " of " << chosen.size()
                                  << " scenarios differ; first: " << mismatches.front().what;
}

// Textbook Dijkstra on the octile rules, with std::priority_queue and lazy
// deletion: shares no code with the planner.
double DijkstraLength(const OccupancyGrid& grid, int sx, int sy, int gx, int gy) {
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> dist(grid.cell_count(), inf);
  using Item = std::pair<double, std::size_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> open;
  dist[grid.Index(sx, sy)] = 0.0;
  open.push({0.0, grid.Index(sx, sy)});
  while (!open.empty()) {
    const auto [d, i] = open.top();
    open.pop();
    if (d > dist[i]) continue;
    const int x = static_cast<int>(i / grid.size_y()), y = static_cast<int>(i % grid.size_y());
    if (x == gx && y == gy) return d;
    for (int dx = -1; dx <= 1; ++dx) {
      for (int dy = -1; dy <= 1; ++dy) {
        if ((dx == 0 && dy == 0) || !grid.IsFree(x + dx, y + dy)) continue;
        if (dx != 0 && dy != 0 && (!grid.IsFree(x + dx, y) || !grid.IsFree(x, y + dy))) continue;
        const double nd = d + ((dx != 0 && dy != 0) ? std::sqrt(2.0) : 1.0);
        const std::size_t j = grid.Index(x + dx, y + dy);
        if (nd < dist[j]) {
          dist[j] = nd;
          open.push({nd, j});
        }
      }
    }
  }
  return inf;
}

TEST(MovingAiOptimality, Den312d) {
  RC_REQUIRE_SHARED_DATA("movingai/den312d.map");
  ExpectScenariosOptimal("den312d.map");
}

TEST(MovingAiOptimality, Boston0_256) {
  RC_REQUIRE_SHARED_DATA("movingai/Boston_0_256.map");
  ExpectScenariosOptimal("Boston_0_256.map");
}

TEST(MovingAiOptimality, Room64_005) {
  RC_REQUIRE_SHARED_DATA("movingai/64room_005.map");
  ExpectScenariosOptimal("64room_005.map", test::FullOrUnderSanitizer(1, 10));
}

TEST(MovingAiOptimality, Maze512_32_9) {
  RC_REQUIRE_SHARED_DATA("movingai/maze512-32-9.map");
  const char* all = std::getenv("RC_MOVINGAI_ALL_BUCKETS");
  const bool every_bucket = all != nullptr && std::string(all) == "1";
  ExpectScenariosOptimal("maze512-32-9.map", every_bucket ? 1 : test::FullOrUnderSanitizer(4, 40));
}

TEST(MovingAiOptimality, IntelMatchesDijkstra) {
  RC_REQUIRE_SHARED_DATA("intel/Intel.map");
  const std::string map_path = test::SharedDataPath("intel/Intel.map");
  const OccupancyGrid grid = LoadMovingAiMap(map_path);
  ASSERT_FALSE(std::filesystem::exists(map_path + ".scen")) << "Intel now has scenarios: test them all here";
  auto planner = GridPlanner::Create(grid, PlannerOptions{});
  // RoWild CarriBot's query, then random pairs of free cells.
  std::vector<std::array<int, 4>> queries = {{227, 33, 59, 217}};
  std::mt19937 rng(12);
  std::uniform_int_distribution<int> x(0, grid.size_x() - 1), y(0, grid.size_y() - 1);
  while (queries.size() < 12) {
    const std::array<int, 4> q{x(rng), y(rng), x(rng), y(rng)};
    if (grid.IsFree(q[0], q[1]) && grid.IsFree(q[2], q[3])) queries.push_back(q);
  }
  int found = 0;
  for (const auto& q : queries) {
    const PlanResult r = planner->Plan({q[0], q[1]}, {q[2], q[3]});
    const double expected = DijkstraLength(grid, q[0], q[1], q[2], q[3]);
    if (std::isinf(expected)) {
      EXPECT_EQ(r.status, PlanStatus::kNoPath);
      continue;
    }
    ASSERT_TRUE(r.found());
    EXPECT_NEAR(r.length_cells, expected, 1e-9);
    ++found;
  }
  EXPECT_GE(found, 6);
}

}  // namespace
}  // namespace rc
