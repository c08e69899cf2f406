// Hand-built degenerate cases for the SACT: touching faces at every scale
// and far from the origin, (anti)parallel and nearly parallel axes,
// edge-edge grazing, zero-thickness boxes, and the stage accounting.
// Each answer is also checked against the exact reference.
#include <cmath>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "overlap_oracle.h"
#include "pair_generator.h"
#include "robocore/collision/exact_overlap_reference.h"
#include "robocore/collision/sact.h"

namespace rc {
namespace {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

Mat3 Rot(const Vec3& axis, double angle) { return Eigen::AngleAxisd(angle, axis.normalized()).matrix(); }

Obbd MakeObb(const Vec3& centre, const Mat3& axes, const Vec3& half) { return Obbd{centre, axes, half}; }

// The OBB's extent along world axis j (exact for signed permutations).
double Extent(const Obbd& obb, int j) {
  double e = 0;
  for (int i = 0; i < 3; ++i) e += std::abs(obb.axes(j, i)) * obb.half[i];
  return e;
}

TEST(SactHardCases, TouchingFacesOverlapAtEveryScaleAndFarFromTheOrigin) {
  const Mat3 rotations[] = {Mat3::Identity(), Rot(Vec3::UnitZ(), M_PI / 2),
                            Rot(Vec3::UnitX(), M_PI),  // anti-parallel y and z
                            Rot(Vec3::UnitX(), M_PI / 2) * Rot(Vec3::UnitY(), M_PI / 2)};
  int cases = 0;
  for (double scale : {1e-3, 1e-1, 1.0, 1e1, 1e3})
    for (double far : {0.0, 1e3, 1e6})
      for (const Mat3& r : rotations)
        for (int j = 0; j < 3; ++j)
          for (double side : {-1.0, 1.0}) {
            const Vec3 offset = far * scale * Vec3(1, -2, 3);
            // Snap the rotation to exact signed-permutation entries.
            const Mat3 axes = r.array().round().matrix();
            Aabbd box{offset, scale * Vec3(0.3, 0.7, 0.4)};
            Obbd obb = MakeObb(offset, axes, scale * Vec3(1.0, 0.5, 0.25));
            const double touch = box.half[j] + Extent(obb, j);
            for (double gap : {0.0, -1e-3, 1e-3}) {
              obb.centre = offset;
              obb.centre[j] += side * (touch + gap * scale);
              const SactResult r = TestObbAabb(obb, box);
              const ExactOverlap exact = ExactObbAabbOverlap(obb, box);
              if (gap == 0) {
                EXPECT_TRUE(r.overlaps()) << "touching, scale " << scale << " far " << far << " axis " << j;
                EXPECT_LE(std::fabs(exact.depth), 1e-12L * (far + 1) * scale);
              } else if (gap < 0) {
                EXPECT_TRUE(r.overlaps());
                EXPECT_GT(exact.depth, 0);
              } else {
                EXPECT_FALSE(r.overlaps()) << "apart by 1e-3 scale";
                EXPECT_LT(r.separating_axis, kSactBoxNormalAxes) << "aligned boxes separate on a face axis";
                EXPECT_LT(exact.depth, 0);
              }
              ++cases;
            }
          }
  EXPECT_EQ(cases, 5 * 3 * 4 * 3 * 2 * 3);
}

TEST(SactHardCases, ParallelEdgesNeverSeparateOnTheirDegenerateCrossAxis) {
  // With an OBB axis (anti)parallel to a world axis, that edge x edge axis is
  // a zero vector; the epsilon must keep it from separating anything.
  const Mat3 rotations[] = {Mat3::Identity(),         -Mat3::Identity(),         Rot(Vec3::UnitZ(), 0.7),
                            Rot(Vec3::UnitX(), -2.1), Rot(Vec3(1, 2, 3), 1e-12), Rot(Vec3(3, -1, 2), 1e-9),
                            Rot(Vec3(-2, 1, 1), 1e-6)};
  int tested = 0;
  for (const Mat3& axes : rotations)
    for (int k = 0; k < 400; ++k) {
      // A deterministic sweep of placements through and around the box.
      const double t = k / 400.0;
      const Vec3 centre(2.2 * std::cos(17 * t) * t, 1.9 * std::sin(11 * t), 1.7 * std::cos(5 * t + 1));
      const Obbd obb = MakeObb(centre, axes, Vec3(0.9, 0.4, 0.6));
      const Aabbd box{Vec3::Zero(), Vec3(0.5, 0.8, 0.3)};
      const SactResult r = TestObbAabb(obb, box);
      if (r.separating_axis >= kSactBoxNormalAxes) {
        const int i = (r.separating_axis - 6) / 3, j = (r.separating_axis - 6) % 3;
        EXPECT_GT(obb.axes.col(i).cross(Vec3::Unit(j)).norm(), 1e-10) << "separated on a degenerate axis";
      }
      const ExactOverlap exact = ExactObbAabbOverlap(obb, box);
      if (std::fabs(exact.depth) > 1e-5L) {
        EXPECT_EQ(r.overlaps(), exact.overlaps()) << k;
      }
      ++tested;
    }
  EXPECT_EQ(tested, 7 * 400);
}

TEST(SactHardCases, EdgeEdgeGrazingIsFoundOnlyByItsEdgeAxis) {
  // Two edges crossing at their midpoints, the boxes on either side of the
  // plane through both edges: no face axis separates, only A_i x B_j does.
  const Mat3 axes = Rot(Vec3::UnitZ(), 0.6) * Rot(Vec3::UnitX(), 0.8) * Rot(Vec3::UnitY(), 0.3);
  const Vec3 ea(0.6, 0.4, 0.5), eb(0.5, 0.3, 0.7);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const Vec3 n = axes.col(i).cross(Vec3::Unit(j)).normalized();
      Vec3 mb = Vec3::Zero(), ma = Vec3::Zero();  // edge midpoints: B's furthest along n, A's along -n
      for (int k = 0; k < 3; ++k) {
        if (k != j) mb[k] = (n[k] < 0 ? -1 : 1) * eb[k];
        if (k != i) ma += (axes.col(k).dot(n) < 0 ? 1 : -1) * ea[k] * axes.col(k);
      }
      for (double gap : {0.0, 1e-3, -1e-3}) {
        const Obbd obb = MakeObb(mb + gap * n - ma, axes, ea);
        const Aabbd box{Vec3::Zero(), eb};
        const SactResult r = TestObbAabb(obb, box);
        const ExactOverlap exact = ExactObbAabbOverlap(obb, box);
        if (gap > 0) {
          EXPECT_EQ(r.separating_axis, 6 + 3 * i + j) << i << j;
          EXPECT_EQ(r.axes_tested, 7 + 3 * i + j);
          EXPECT_TRUE(test::AxisSeparates(obb, box, r.separating_axis));
          EXPECT_LT(exact.depth, 0);
        } else {
          EXPECT_TRUE(r.overlaps()) << i << j << " gap " << gap;
          EXPECT_GE(exact.depth, gap == 0 ? -1e-14L : 0.0L);
        }
      }
    }
}

TEST(SactHardCases, ZeroThicknessBoxes) {
  const Aabbd box{Vec3(1, 2, 3), Vec3(0.5, 0.25, 1.0)};
  const Mat3 tilt = Rot(Vec3(1, 1, 0), 0.4);
  // A rectangle (no thickness) lying on the box's top face, then lifted.
  Obbd sheet = MakeObb(Vec3(1.1, 2.0, 4.0), Mat3::Identity(), Vec3(0.2, 0.2, 0));
  EXPECT_TRUE(TestObbAabb(sheet, box).overlaps());
  sheet.centre.z() = 4.0 + 1e-4;
  EXPECT_FALSE(TestObbAabb(sheet, box).overlaps());
  // A segment through the box, and one passing beside a vertical edge.
  Obbd segment = MakeObb(box.centre, tilt, Vec3(3, 0, 0));
  EXPECT_TRUE(TestObbAabb(segment, box).overlaps());
  segment = MakeObb(Vec3(1.5 + 0.1, 2.25 + 0.1, 3), Rot(Vec3::UnitZ(), M_PI / 4), Vec3(0, 1, 0));
  EXPECT_FALSE(TestObbAabb(segment, box).overlaps());
  // A point inside, on a face, on a vertex, and just outside.
  const Vec3 zero = Vec3::Zero();
  EXPECT_TRUE(TestObbAabb(MakeObb(Vec3(1.2, 2.1, 3.5), tilt, zero), box).overlaps());
  EXPECT_TRUE(TestObbAabb(MakeObb(Vec3(1.5, 2.1, 3.5), tilt, zero), box).overlaps());
  EXPECT_TRUE(TestObbAabb(MakeObb(Vec3(1.5, 2.25, 4.0), tilt, zero), box).overlaps());
  EXPECT_FALSE(TestObbAabb(MakeObb(Vec3(1.5 + 1e-9, 2.1, 3.5), tilt, zero), box).overlaps());
  // Two coplanar squares of zero thickness: overlapping, then apart.
  const Aabbd flat{Vec3(0, 0, 0), Vec3(1, 1, 0)};
  EXPECT_TRUE(TestObbAabb(MakeObb(Vec3(1.5, 0, 0), Rot(Vec3::UnitZ(), 0.3), Vec3(0.6, 0.6, 0)), flat).overlaps());
  EXPECT_FALSE(TestObbAabb(MakeObb(Vec3(2.5, 0, 0), Rot(Vec3::UnitZ(), 0.3), Vec3(0.6, 0.6, 0)), flat).overlaps());
  // The reference agrees on the clear cases.
  EXPECT_LT(ExactObbAabbOverlap(MakeObb(Vec3(2.5, 0, 0), Rot(Vec3::UnitZ(), 0.3), Vec3(0.6, 0.6, 0)), flat).depth, 0);
  EXPECT_NEAR(static_cast<double>(ExactObbAabbOverlap(MakeObb(Vec3(1.5, 2.25, 4.0), tilt, zero), box).depth), 0, 1e-15);
}

TEST(SactHardCases, StagesFollowTheExitAxis) {
  // Every exit 0..14 and the overlap, from the generated pairs.
  std::vector<bool> seen(kSactAxisCount + 1, false);
  for (std::uint64_t i = 0; i < 200'000 && std::count(seen.begin(), seen.end(), false) > 0; ++i) {
    const test::ObbAabbPair p = test::GeneratePair(99, i);
    const SactResult r = TestObbAabb(p.obb, p.box);
    seen[r.overlaps() ? kSactAxisCount : r.separating_axis] = true;
    const SactStageCounts c = StagesOf(r, false);
    EXPECT_EQ(r.axes_tested, r.overlaps() ? kSactAxisCount : r.separating_axis + 1);
    EXPECT_EQ(c.pre_process, 1);
    EXPECT_EQ(c.box_normal + c.edge_edge, r.axes_tested);
    EXPECT_EQ(c.box_normal, std::min<int>(r.axes_tested, 6));
    std::vector<SactStage> stages;
    AppendStages(r, false, stages);
    ASSERT_EQ(stages.size(), 1u + r.axes_tested);
    EXPECT_EQ(OpcodeOf(stages.front()), Opcode::kPre);
    for (std::size_t k = 1; k < stages.size(); ++k)
      EXPECT_EQ(OpcodeOf(stages[k]), k <= 6 ? Opcode::kBox : Opcode::kEdge);
  }
  for (int k = 0; k <= kSactAxisCount; ++k) EXPECT_TRUE(seen[k]) << "exit " << k << " never seen";
  EXPECT_EQ(SactAxisName(0), "A0");
  EXPECT_EQ(SactAxisName(5), "B2");
  EXPECT_EQ(SactAxisName(6 + 3 * 2 + 1), "A2xB1");
}

TEST(SactHardCases, SpherePretestsDecideOnlyClearCases) {
  SactOptions<double> o;
  o.sphere_pretests = true;
  const Aabbd box{Vec3::Zero(), Vec3(1, 1, 1)};
  const Mat3 axes = Rot(Vec3(1, 2, 3), 0.5);
  const SactResult far = TestObbAabb(MakeObb(Vec3(10, 0, 0), axes, Vec3(1, 1, 1)), box, o);
  EXPECT_EQ(far.decided_by, SactDecision::kOuterSphereReject);
  EXPECT_EQ(far.separating_axis, kSactSphereSeparated);
  EXPECT_FALSE(far.overlaps());
  const SactResult deep = TestObbAabb(MakeObb(Vec3(0.5, 0, 0), axes, Vec3(1, 1, 1)), box, o);
  EXPECT_EQ(deep.decided_by, SactDecision::kInnerSphereAccept);
  EXPECT_TRUE(deep.overlaps());
  EXPECT_EQ(StagesOf(deep, true).pre_process, 0);
  EXPECT_EQ(StagesOf(deep, true).sphere_pretests, 1);
  // Between the spheres: the axes decide (corner-to-corner, 0.1 apart).
  const SactResult near = TestObbAabb(MakeObb(Vec3(2.1, 2.1, 0), Mat3::Identity(), Vec3(1, 1, 1)), box, o);
  EXPECT_EQ(near.decided_by, SactDecision::kAxes);
  EXPECT_FALSE(near.overlaps());
}

TEST(SactHardCases, ArtifactConventionIsInvisibleWithoutRotation) {
  // Why a test with only axis-aligned OBBs cannot catch the artifact's bug:
  // for a symmetric rotation matrix rows and columns coincide.
  SactOptions<double> artifact;
  artifact.convention = TranslationConvention::kArtifactRows;
  const Aabbd box{Vec3::Zero(), Vec3(1, 1, 1)};
  const Mat3 rotated = Rot(Vec3::UnitZ(), 0.9);
  int differ_aligned = 0, differ_rotated = 0;
  for (int k = 0; k < 2000; ++k) {
    const Vec3 c(3 * std::cos(0.37 * k), 3 * std::sin(0.61 * k), 0.2 * std::cos(0.11 * k));
    const Obbd aligned = MakeObb(c, Mat3::Identity(), Vec3(1.2, 0.3, 0.5));
    const Obbd turned = MakeObb(c, rotated, Vec3(1.2, 0.3, 0.5));
    differ_aligned += TestObbAabb(aligned, box).overlaps() != TestObbAabb(aligned, box, artifact).overlaps();
    differ_rotated += TestObbAabb(turned, box).overlaps() != TestObbAabb(turned, box, artifact).overlaps();
  }
  EXPECT_EQ(differ_aligned, 0);
  EXPECT_GT(differ_rotated, 0);
}

}  // namespace
}  // namespace rc
