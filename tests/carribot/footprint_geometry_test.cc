// The exact footprint-vs-cell tests against independent references: polygon
// clipping for still and translated boxes, dense sampling for turns, and
// hand-made contacts that must be decided exactly.
#include "workloads/carribot/footprint_geometry.h"

#include <gtest/gtest.h>

#include <random>

#include "carribot/brute_force_geometry.h"

namespace rc {
namespace {

constexpr double kTwoPi = 6.283185307179586;

struct RandomBox {
  Vec2 center;
  CenteredBox box;
};

RandomBox DrawBox(std::mt19937& rng) {
  std::uniform_real_distribution<double> pos(0.0, 6.0), angle(0.0, kTwoPi), extent(0.0, 2.5);
  std::bernoulli_distribution degenerate(0.1);
  RandomBox b;
  b.center = {pos(rng), pos(rng)};
  const double a = angle(rng);
  b.box.axis = {std::cos(a), std::sin(a)};
  b.box.half_length = extent(rng);
  b.box.half_width = degenerate(rng) ? 0.0 : extent(rng);
  return b;
}

CellSquare RelativeSquare(int ix, int iy, Vec2 c) { return {{ix - c.x, iy - c.y}, {ix + 1 - c.x, iy + 1 - c.y}}; }

TEST(FootprintGeometry, BoxAgreesWithPolygonClippingOnRandomRectangles) {
  std::mt19937 rng(7);
  int touching = 0, total = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const RandomBox b = DrawBox(rng);
    const test::Polygon poly = test::BoxPolygon(b.center, b.box.half_length, b.box.half_width, b.box.axis);
    for (int ix = -3; ix < 10; ++ix) {
      for (int iy = -3; iy < 10; ++iy) {
        const bool expected = test::PolygonTouchesSquare(poly, {double(ix), double(iy)}, {ix + 1.0, iy + 1.0});
        ASSERT_EQ(BoxTouchesSquare(b.box, RelativeSquare(ix, iy, b.center)), expected)
            << "trial " << trial << " cell " << ix << "," << iy;
        touching += expected;
        ++total;
      }
    }
  }
  EXPECT_GT(touching, total / 50);  // the sample is not trivially all-false
}

TEST(FootprintGeometry, TranslatedBoxAgreesWithHullClipping) {
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> step(-1, 1);
  for (int trial = 0; trial < 3000; ++trial) {
    const RandomBox b = DrawBox(rng);
    const Vec2 d{double(step(rng)), double(step(rng))};
    test::Polygon points = test::BoxPolygon(b.center, b.box.half_length, b.box.half_width, b.box.axis);
    for (const Vec2 p :
         test::BoxPolygon({b.center.x + d.x, b.center.y + d.y}, b.box.half_length, b.box.half_width, b.box.axis))
      points.push_back(p);
    const test::Polygon hull = test::ConvexHull(points);
    for (int ix = -3; ix < 10; ++ix)
      for (int iy = -3; iy < 10; ++iy)
        ASSERT_EQ(
            SweptBoxTouchesSquare(b.box, d, RelativeSquare(ix, iy, b.center)),
            test::PolygonTouchesSquare(hull.empty() ? points : hull, {double(ix), double(iy)}, {ix + 1.0, iy + 1.0}))
            << "trial " << trial << " cell " << ix << "," << iy;
  }
}

// A turn is checked against the union of densely sampled intermediate boxes:
// every cell a sample touches must be reported (no false negative), and a
// reported cell must be touched by some sample grown by the largest distance a
// point moves between two samples (no false positive beyond that).
TEST(FootprintGeometry, TurnAgreesWithDenseSampling) {
  std::mt19937 rng(13);
  constexpr int kSamples = 200;
  for (int trial = 0; trial < 160; ++trial) {
    RandomBox b = DrawBox(rng);
    b.center = {0.5, 0.5};
    const double start = std::atan2(b.box.axis.y, b.box.axis.x);
    const double turn = kTwoPi / (trial % 2 == 0 ? 8 : 16);
    const Vec2 end_axis{std::cos(start + turn), std::sin(start + turn)};
    const double radius = std::hypot(b.box.half_length, b.box.half_width);
    const double slack = radius * turn / kSamples;
    for (int ix = -4; ix < 5; ++ix) {
      for (int iy = -4; iy < 5; ++iy) {
        bool hit = false, near = false;
        for (int k = 0; k <= kSamples && !hit; ++k) {
          const double a = start + turn * k / kSamples;
          const Vec2 axis{std::cos(a), std::sin(a)};
          const Vec2 lo{double(ix), double(iy)}, hi{ix + 1.0, iy + 1.0};
          hit =
              test::PolygonTouchesSquare(test::BoxPolygon(b.center, b.box.half_length, b.box.half_width, axis), lo, hi);
          near = near ||
                 test::PolygonTouchesSquare(
                     test::BoxPolygon(b.center, b.box.half_length + slack, b.box.half_width + slack, axis), lo, hi);
        }
        const bool exact = RotationSweepTouchesSquare(b.box, end_axis, RelativeSquare(ix, iy, b.center));
        if (hit) {
          ASSERT_TRUE(exact) << "missed cell " << ix << "," << iy << " trial " << trial;
        }
        if (exact) {
          ASSERT_TRUE(hit || near) << "spurious cell " << ix << "," << iy << " trial " << trial;
        }
      }
    }
  }
}

TEST(FootprintGeometry, ExactContactsCountAsCollisions) {
  // A 1 x 1 box on a cell centre touches all eight neighbours (touching counts).
  const CenteredBox unit{0.5, 0.5, HeadingAxis(0, 8)};
  for (int dx = -1; dx <= 1; ++dx)
    for (int dy = -1; dy <= 1; ++dy) EXPECT_TRUE(BoxTouchesSquare(unit, OffsetCellSquare(dx, dy)));
  EXPECT_FALSE(BoxTouchesSquare(unit, OffsetCellSquare(2, 0)));
  // Slightly smaller: only its own cell.
  const CenteredBox smaller{0.4999, 0.4999, HeadingAxis(2, 8)};
  EXPECT_TRUE(BoxTouchesSquare(smaller, OffsetCellSquare(0, 0)));
  EXPECT_FALSE(BoxTouchesSquare(smaller, OffsetCellSquare(1, 0)));
  EXPECT_FALSE(BoxTouchesSquare(smaller, OffsetCellSquare(1, 1)));
  // Quarter turns are exact: 3 x 1 at 90 degrees spans 3 columns x 5 rows.
  const CenteredBox bar{1.5, 0.5, HeadingAxis(4, 16)};
  EXPECT_TRUE(BoxTouchesSquare(bar, OffsetCellSquare(1, 2)));
  EXPECT_FALSE(BoxTouchesSquare(bar, OffsetCellSquare(2, 0)));
  EXPECT_FALSE(BoxTouchesSquare(bar, OffsetCellSquare(0, 3)));
  // A point on a cell centre moving diagonally touches both corner cells.
  const CenteredBox point{0.0, 0.0, HeadingAxis(1, 8)};
  EXPECT_TRUE(SweptBoxTouchesSquare(point, {1, 1}, OffsetCellSquare(1, 0)));
  EXPECT_TRUE(SweptBoxTouchesSquare(point, {1, 1}, OffsetCellSquare(0, 1)));
  EXPECT_FALSE(SweptBoxTouchesSquare(point, {1, 1}, OffsetCellSquare(-1, 1)));
  EXPECT_FALSE(SweptBoxTouchesSquare(point, {1, 0}, OffsetCellSquare(0, 1)));
}

TEST(FootprintGeometry, HeadingAxesAreExactAndSymmetric) {
  for (const int n : {4, 8, 16}) {
    for (int k = 0; k < n; ++k) {
      const Vec2 u = HeadingAxis(k, n);
      EXPECT_NEAR(std::hypot(u.x, u.y), 1.0, 1e-15);
      EXPECT_NEAR(std::remainder(std::atan2(u.y, u.x) - kTwoPi * k / n, kTwoPi), 0.0, 1e-12);
      if ((4 * k) % n == 0) {
        EXPECT_TRUE(u.x == 0.0 || u.y == 0.0);
      }
    }
  }
  const Vec2 diagonal = HeadingAxis(1, 8);
  EXPECT_EQ(diagonal.x, diagonal.y);
}

TEST(FootprintGeometry, SectorContainsItsArcAndNothingBeyond) {
  const Sector quarter{2.0, {1.0, 0.0}, {0.0, 1.0}};
  EXPECT_TRUE(SectorTouchesSquare(quarter, {{1.0, 1.0}, {1.2, 1.2}}));     // inside
  EXPECT_FALSE(SectorTouchesSquare(quarter, {{1.5, 1.5}, {2.0, 2.0}}));    // beyond the radius
  EXPECT_FALSE(SectorTouchesSquare(quarter, {{-2.0, 0.5}, {-1.0, 1.0}}));  // outside the wedge
  EXPECT_TRUE(SectorTouchesSquare(quarter, {{2.0, -1.0}, {3.0, 0.0}}));    // touches the arc end (2, 0)
  EXPECT_TRUE(SectorTouchesSquare(quarter, {{-1.0, -1.0}, {0.0, 0.0}}));   // touches the apex
}

}  // namespace
}  // namespace rc
