// The exact overlap reference itself: analytic depths, its two LP methods
// against each other, and the signs of the constructed contacts.
#include <cmath>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "pair_generator.h"
#include "robocore/collision/exact_overlap_reference.h"
#include "robocore/collision/small_lp.h"

namespace rc {
namespace {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

TEST(ExactReference, IdenticalBoxesOverlapByTheSmallestHalfExtent) {
  const Mat3 axes = Mat3::Identity();
  const ExactOverlap e =
      ExactObbAabbOverlap(Obbd{Vec3(1, 2, 3), axes, Vec3(0.5, 0.2, 0.9)}, Aabbd{Vec3(1, 2, 3), Vec3(0.5, 0.2, 0.9)});
  EXPECT_NEAR(static_cast<double>(e.depth), 0.2, 1e-15);
}

TEST(ExactReference, AlignedBoxesApartAlongXNeedHalfTheGap) {
  for (double gap : {-0.5, -1e-9, 0.0, 1e-9, 0.25, 3.0}) {
    const ExactOverlap e = ExactObbAabbOverlap(Obbd{Vec3(2 + gap, 0, 0), Mat3::Identity(), Vec3(1, 1, 1)},
                                               Aabbd{Vec3::Zero(), Vec3(1, 1, 1)});
    EXPECT_NEAR(static_cast<double>(e.depth), -gap / 2, 1e-15) << gap;
    EXPECT_EQ(e.overlaps(), gap <= 0);
  }
}

TEST(ExactReference, CubeTurnedFortyFiveDegrees) {
  // A unit cube turned 45 degrees about z reaches sqrt(2) along x; shrunk by
  // s both reach (1 - s)(1 + sqrt 2), so s* = 1 - d / (1 + sqrt 2).
  const Mat3 axes = Eigen::AngleAxisd(M_PI / 4, Vec3::UnitZ()).matrix();
  for (double d : {1.0, 2.0, 2.4, 3.0, 5.0}) {
    const ExactOverlap e =
        ExactObbAabbOverlap(Obbd{Vec3::Zero(), axes, Vec3(1, 1, 1)}, Aabbd{Vec3(d, 0, 0), Vec3(1, 1, 1)});
    EXPECT_NEAR(static_cast<double>(e.depth), 1 - d / (1 + std::sqrt(2.0)), 1e-14) << d;
    // The witness lies in both boxes shrunk by s*.
    const Vec3ld w = e.witness;
    for (int i = 0; i < 3; ++i) EXPECT_LE(std::fabs(axes.col(i).cast<long double>().dot(w)), 1 - e.depth + 1e-15L);
    EXPECT_LE(std::fabs(w[0] - d), 1 - e.depth + 1e-15L);
  }
}

TEST(ExactReference, SimplexAgreesWithVertexEnumeration) {
  int fallbacks = 0;
  for (std::uint64_t i = 0; i < 5000; ++i) {
    const test::ObbAabbPair p = test::GeneratePair(7, i);
    const std::vector<LpRow> rows = OverlapLpRows(p.obb, p.box);
    const long double tol = OverlapLpTolerance(rows);
    LpVector start{0, 0, 0, rows.front().rhs};
    for (const LpRow& r : rows) start[3] = std::min(start[3], r.rhs);
    const LpSolution simplex = MaximizeBySimplex(rows, {0, 0, 0, 1}, start, tol);
    const LpSolution enumerated = MaximizeByVertexEnumeration(rows, {0, 0, 0, 1}, tol);
    ASSERT_TRUE(enumerated.solved) << i;
    if (!simplex.solved) {
      ++fallbacks;
      continue;
    }
    long double scale = 0;
    for (const LpRow& r : rows) scale = std::max(scale, std::fabs(r.rhs));
    EXPECT_LE(std::fabs(simplex.value - enumerated.value), 1e-13L * scale) << i;
  }
  EXPECT_LT(fallbacks, 5) << "the simplex should rarely need its fallback";
}

TEST(ExactReference, ConstructedContactsHaveTheConstructedSign) {
  int checked = 0;
  for (std::uint64_t i = 0; i < 20000; ++i) {
    const test::ObbAabbPair p = test::GeneratePair(11, i);
    if (p.family == test::PairFamily::kGeneric) continue;
    if ((p.obb.half.array() == 0).any() || (p.box.half.array() == 0).any()) continue;
    const long double s = p.obb.half.sum() + p.box.half.sum();
    const ExactOverlap e = ExactObbAabbOverlap(p.obb, p.box);
    if (p.gap == 0) {
      EXPECT_LE(std::fabs(e.depth), 1e-9L * s) << i << " " << ToString(p.family);
    } else if (std::fabs(p.gap) >= 1e-6 * s) {
      EXPECT_EQ(e.overlaps(), p.gap < 0) << i << " " << ToString(p.family) << " gap " << p.gap;
    }
    ++checked;
  }
  EXPECT_GT(checked, 10000);
}

}  // namespace
}  // namespace rc
