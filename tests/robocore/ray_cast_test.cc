// Ray-casting kernels against an independent reference, plus the geometry
// degeneracies DESIGN.md asks for: rays along grid lines, through cell
// corners, starting on the map edge, starting inside a wall, and maps with
// no free cell.
#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "common/angles.h"
#include "common/random_stream.h"
#include "robocore/ray_batch.h"
#include "robocore/ray_cast.h"
#include "support/random_grid.h"

namespace rc {
namespace {

using test::RandomGrid;

// Independent reference: the earliest time the ray is inside a stopping cell
// or outside the map, with cells as half-open squares [lo, hi). Derived per
// cell with interval arithmetic rather than by traversal.
double ReferenceRange(const OccupancyGrid& g, double ox, double oy, double angle, double max_range) {
  const double dx = std::cos(angle), dy = std::sin(angle), r = g.resolution_m();
  auto axis_interval = [](double o, double d, double lo, double hi, double& t0, double& t1) {
    if (d == 0.0) {
      if (o >= lo && o < hi) {
        t0 = -std::numeric_limits<double>::infinity();
        t1 = std::numeric_limits<double>::infinity();
        return true;
      }
      return false;
    }
    const double a = (lo - o) / d, b = (hi - o) / d;
    t0 = std::min(a, b);
    t1 = std::max(a, b);
    return true;
  };
  double best = max_range;
  for (int x = 0; x < g.size_x(); ++x)
    for (int y = 0; y < g.size_y(); ++y) {
      if (g.At(x, y) == CellState::kFree) continue;
      double ax0, ax1, ay0, ay1;
      if (!axis_interval(ox, dx, x * r, (x + 1) * r, ax0, ax1)) continue;
      if (!axis_interval(oy, dy, y * r, (y + 1) * r, ay0, ay1)) continue;
      const double t0 = std::max({ax0, ay0, 0.0}), t1 = std::min(ax1, ay1);
      if (t0 < t1) best = std::min(best, t0);
    }
  // Leaving the map: the ray's exit time from the map rectangle.
  double ex0 = 0, ex1 = 0, ey0 = 0, ey1 = 0;
  axis_interval(ox, dx, 0.0, g.extent_x_m(), ex0, ex1);
  axis_interval(oy, dy, 0.0, g.extent_y_m(), ey0, ey1);
  best = std::min(best, std::max(0.0, std::min(ex1, ey1)));
  return best;
}

struct RandomRay {
  double x, y, a;
};

std::vector<RandomRay> RandomRays(const OccupancyGrid& g, int n, std::uint64_t seed) {
  std::vector<RandomRay> rays;
  RandomStream s(seed, StreamPurpose::kTest, 1, 0);
  while (static_cast<int>(rays.size()) < n) {
    RandomRay ray{s.Uniform(0, g.extent_x_m()), s.Uniform(0, g.extent_y_m()), s.Uniform(-kPi, kPi)};
    if (g.IsFreePoint(ray.x, ray.y)) rays.push_back(ray);
  }
  return rays;
}

TEST(RayCastTest, DdaMatchesIndependentReferenceOnRandomMaps) {
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const OccupancyGrid g = RandomGrid(37, 29, 0.1, 0.08, seed);
    const RayCastScene scene(g, RayCastMethod::kDda);
    for (const auto& ray : RandomRays(g, 1500, seed)) {
      const double expected = ReferenceRange(g, ray.x, ray.y, ray.a, 2.5);
      const RayHit hit = CastRay(scene, ray.x, ray.y, ray.a, 2.5);
      ASSERT_NEAR(hit.range_m, expected, 1e-5) << "seed " << seed << " ray " << ray.x << "," << ray.y << "," << ray.a;
    }
  }
}

TEST(RayCastTest, RayMarchingEqualsDdaExactly) {
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const OccupancyGrid g = RandomGrid(300, 200, 0.05, 0.002, seed);  // open map: long jumps
    const RayCastScene dda(g, RayCastMethod::kDda), rm(g, RayCastMethod::kRayMarching);
    ASSERT_NE(rm.distance_field(), nullptr);
    ASSERT_EQ(dda.distance_field(), nullptr) << "dda must not build a distance field";
    std::uint64_t dda_nodes = 0, rm_nodes = 0;
    for (const auto& ray : RandomRays(g, 20000, seed)) {
      const RayHit a = CastRay(dda, ray.x, ray.y, ray.a, 12.0);
      const RayHit b = CastRay(rm, ray.x, ray.y, ray.a, 12.0);
      ASSERT_EQ(a.range_m, b.range_m) << ray.x << "," << ray.y << "," << ray.a;
      dda_nodes += a.nodes;
      rm_nodes += b.nodes;
    }
    EXPECT_LT(rm_nodes, dda_nodes / 2) << "ray marching should skip open space";
  }
}

TEST(RayCastTest, MarchSamplesEveryCellSizeAlongTheRay) {
  OccupancyGrid g(20, 5, 0.1);
  g.Set(12, 2, CellState::kOccupied);
  const RayCastScene scene(g, RayCastMethod::kMarch);
  // From the centre of cell (2, 2) along +x: samples at 0.25, 0.35, ...;
  // the first sample in cell 12 is at x = 1.25, k = 10 steps.
  const RayHit hit = CastRay(scene, 0.25, 0.25, 0.0, 5.0);
  EXPECT_NEAR(hit.range_m, 1.0, 1e-6);
  EXPECT_EQ(hit.nodes, 11u);
}

TEST(RayCastTest, MarchCanSkipAClippedCornerButDdaCannot) {
  OccupancyGrid g(10, 10, 1.0);
  g.Set(5, 5, CellState::kOccupied);
  const RayCastScene dda(g, RayCastMethod::kDda), march(g, RayCastMethod::kMarch);
  // Sweep a fan of rays past the cell's corner: some clip it over a chord
  // shorter than march's step. dda must see every one of them.
  int skipped = 0;
  for (int i = 0; i < 2000; ++i) {
    const double angle = 0.70 + 0.2 * i / 2000.0;
    const RayHit exact = CastRay(dda, 0.5, 0.5, angle, 20.0);
    ASSERT_NEAR(exact.range_m, ReferenceRange(g, 0.5, 0.5, angle, 20.0), 1e-5);
    const RayHit sampled = CastRay(march, 0.5, 0.5, angle, 20.0);
    if (sampled.range_m > exact.range_m + 1.0) ++skipped;
  }
  EXPECT_GT(skipped, 0) << "march should step over some clipped corners";
}

TEST(RayCastTest, RaysAlongGridLinesBelongToTheCellAboveTheLine) {
  // Resolution 0.25 m is exact in binary, so the origin lies exactly on a line.
  OccupancyGrid g(16, 16, 0.25);
  for (int x = 0; x < 16; ++x) g.Set(x, 3, CellState::kOccupied);  // a wall just below y = 1.0
  for (auto method : {RayCastMethod::kDda, RayCastMethod::kRayMarching, RayCastMethod::kMarch}) {
    const RayCastScene scene(g, method);
    // march samples every cell size, so it may overshoot by up to one step.
    const double tol = method == RayCastMethod::kMarch ? 0.25 + 1e-6 : 1e-6;
    // Along y = 1.0 (the wall's top face) in +x and -x: the ray lives in row
    // 4 and grazes the wall without entering it; it stops at the map border.
    EXPECT_NEAR(CastRay(scene, 0.5, 1.0, 0.0, 10.0).range_m, 3.5, tol) << ToString(method);
    EXPECT_NEAR(CastRay(scene, 3.5, 1.0, kPi, 10.0).range_m, 3.5, tol) << ToString(method);
    // Straight down onto the wall from y = 2.0: enters row 3 at y = 1.0.
    EXPECT_NEAR(CastRay(scene, 1.0, 2.0, -kPi / 2, 10.0).range_m, 1.0, tol) << ToString(method);
  }
}

TEST(RayCastTest, DiagonalThroughCellCornersCannotSlipBetweenDiagonalWallCells) {
  OccupancyGrid g(10, 10, 0.25);
  g.Set(5, 4, CellState::kOccupied);  // two wall cells touching at the corner (1.25, 1.25)
  g.Set(4, 5, CellState::kOccupied);
  for (auto method : {RayCastMethod::kDda, RayCastMethod::kRayMarching}) {
    const RayCastScene scene(g, method);
    // From the corner (0.25, 0.25) at 45 degrees, passing exactly through
    // the corners (0.5, 0.5), ..., (1.25, 1.25).
    const RayHit hit = CastRay(scene, 0.25, 0.25, kPi / 4, 10.0);
    EXPECT_NEAR(hit.range_m, std::sqrt(2.0), 1e-6) << ToString(method);
  }
}

TEST(RayCastTest, RaysStartingOnTheMapEdge) {
  OccupancyGrid g(8, 8, 0.25);
  for (auto method : {RayCastMethod::kDda, RayCastMethod::kRayMarching, RayCastMethod::kMarch}) {
    const RayCastScene scene(g, method);
    const double tol = method == RayCastMethod::kMarch ? 0.25 + 1e-6 : 1e-6;
    // On the lower-left corner, pointing inwards: crosses the whole map.
    EXPECT_NEAR(CastRay(scene, 0.0, 0.0, 0.0, 10.0).range_m, 2.0, tol) << ToString(method);
    // On the left edge pointing out: the outside stops it at once.
    EXPECT_NEAR(CastRay(scene, 0.0, 1.0, kPi, 10.0).range_m, 0.0, tol) << ToString(method);
    // Exactly on the far edge x = extent: that point is already outside.
    EXPECT_EQ(CastRay(scene, 2.0, 1.0, kPi, 10.0).range_m, 0.0f) << ToString(method);
  }
}

TEST(RayCastTest, OriginInsideAWallAndMapsWithoutFreeCells) {
  OccupancyGrid walls(6, 6, 0.5, CellState::kOccupied);
  OccupancyGrid unknown(6, 6, 0.5, CellState::kUnknown);
  for (const OccupancyGrid* g : {&walls, &unknown})
    for (auto method : {RayCastMethod::kDda, RayCastMethod::kRayMarching, RayCastMethod::kMarch}) {
      const RayHit hit = CastRay(RayCastScene(*g, method), 1.3, 1.7, 0.3, 10.0);
      EXPECT_EQ(hit.range_m, 0.0f) << ToString(method);
      EXPECT_EQ(hit.nodes, 1u);
    }
}

TEST(RayCastTest, MaxRangeCapsOpenViews) {
  OccupancyGrid g(400, 10, 0.05);
  for (auto method : {RayCastMethod::kDda, RayCastMethod::kRayMarching, RayCastMethod::kMarch}) {
    const RayHit hit = CastRay(RayCastScene(g, method), 0.1, 0.25, 0.0, 3.0);
    EXPECT_NEAR(hit.range_m, 3.0, 1e-6) << ToString(method);
  }
}

TEST(RayCastTest, BatchEqualsSingleQueries) {
  const OccupancyGrid g = RandomGrid(60, 50, 0.1, 0.05, 9);
  const RayCastScene scene(g, RayCastMethod::kRayMarching);
  RayBatch batch;
  batch.max_range_m = 4.0;
  for (const auto& ray : RandomRays(g, 500, 9)) batch.queries.push_back({ray.x, ray.y, ray.a});
  std::vector<RayHit> hits;
  CastRayBatch(scene, batch, hits);
  ASSERT_EQ(hits.size(), batch.queries.size());
  for (std::size_t i = 0; i < hits.size(); ++i) {
    const auto& q = batch.queries[i];
    const RayHit single = CastRay(scene, q.origin_x_m, q.origin_y_m, q.angle_rad, 4.0);
    EXPECT_EQ(hits[i].range_m, single.range_m);
    EXPECT_EQ(hits[i].nodes, single.nodes);
  }
}

}  // namespace
}  // namespace rc
