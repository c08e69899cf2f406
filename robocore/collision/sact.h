#pragma once
// The staged separating-axis test (SACT) of an OBB against an AABB: the
// collision kernel's per-node test (RoboGPU paper, "SACT on TTA+"; the test
// itself is Gottschalk's OBBTree test as written in Ericson, Real-Time
// Collision Detection, 4.4.1, and FCL's obbDisjoint).
//
// Axis order (stage order, and the numbering every record, CSV and the
// shipped program programs/sact_obb_aabb.asm use; RETURN_IF #k there is
// axis k here):
//   0..2   the OBB's face normals A0, A1, A2        (box-normal stage)
//   3..5   the AABB's face normals x, y, z (B0..B2)  (box-normal stage)
//   6..14  the edge x edge axes A_i x B_j, axis 6 + 3 i + j (edge stage)
// One pre-process computes the relative frame first. The test stops at the
// first separating axis; `axes_tested` is then that axis + 1, and 15 when
// no axis separates (overlap).
//
// Touching counts as overlap: an axis separates only when the centre
// distance is strictly greater than the sum of the projected radii
// (`>`; `<=` means the projections share at least a point).
//
// Epsilon: `parallel_epsilon` (default 1e-6, as FCL and the artifact) is
// added to every |R_ij|. When an OBB edge is (anti)parallel to an AABB edge
// their cross product is a near-zero vector; distance and radii along it are
// then rounding noise, and noise can "separate" boxes that overlap. The
// epsilon gives every radius a floor proportional to the box sizes, so a
// degenerate axis never separates. Its price is a band of false overlaps
// for boxes closer than about epsilon x their sizes (see below).
//
// Error band, measured by tests/collision/sact_property_test.cc against the
// exact reference (exact_overlap_reference.h) on 10^6 random pairs, 60% of
// them built at or within 1e-15..1e-1 of exact contact. s* is the
// reference's signed depth (how far every half extent of both boxes must
// shrink (s* > 0) or grow (s* < 0) for the boxes to just touch), S the sum
// of the six half extents, M = max(S, largest |centre coordinate|),
// u the unit roundoff (2^-53 double, 2^-24 float).
//   double: no false separation (touching is always overlap). False
//           overlaps (23% of these contact-heavy pairs) are exactly the
//           ones the epsilon allows: on each of the 15 axes the exact gap
//           is at most epsilon x the half extents that multiply |R| there.
//           In depth: |s*| <= 3.5e-5 S measured. For an edge x edge axis
//           the bound is epsilon x S / (2 sin theta), theta the angle
//           between the two edges, so nearly parallel edges widen it.
//   float:  inputs rounded to float. False separations only at contact,
//           s* <= 0.61 u M measured (<= 8 u M asserted); false overlaps as
//           in double plus rounding: |s*| <= 3.5e-5 M measured.
//   epsilon 0 (for comparison): every error is rounding-level (|s*| <=
//           3e-16 S; R needs no arithmetic for an AABB), but about 2% of
//           exactly touching pairs then come out separated: "touching
//           counts" would hold only by luck. Hence the epsilon.
// The artifact's convention (kArtifactRows) is outside any band: 13% of
// these pairs wrong, and 25 of the 70 mpnet_master OBBs against the shelf
// scene.
//
// Micro-op accounting: the stages a test executed follow from
// `axes_tested` alone (fixed stage order), so a result is a complete record
// for pricing: StagesOf() counts PRE / BOX / EDGE, and OpcodeOf() names the
// micro-ops of robocore/micro_op.h (Opcode::kPre, kBox, kEdge) that the
// RoboCore datapath runs natively and TTA+ expands (TtaPlusExpansion:
// PRE = 4 VEC3-SUB + 1 R-XFORM, BOX = 2 DOT + 1 VEC3-SUB + 1 VEC3-CMP,
// EDGE = 1 CROSS + 1 VEC3-CMP; 47 micro-ops for a full test).
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "robocore/collision/aabb.h"
#include "robocore/collision/obb.h"
// Only the Opcode enum is used (header-only), so rc_collision does not link
// rc_robocore, and rc_robocore may later link rc_collision without a cycle.
#include "robocore/micro_op.h"

namespace rc {

inline constexpr int kSactAxisCount = 15;
inline constexpr int kSactBoxNormalAxes = 6;
inline constexpr std::int8_t kSactOverlap = -1;          // "no axis separates"
inline constexpr std::int8_t kSactSphereSeparated = -2;  // outer sphere pre-test rejected

// How the translation between the boxes is put into the OBB frame.
enum class TranslationConvention : std::uint8_t {
  kBoxFrame,      // t = axes^T (c_B - c_A): projections on the axis columns (correct)
  kArtifactRows,  // t = axes (c_B - c_A): the artifact's bug (REFERENCE.md section 2),
                  // kept so tests and studies can show what it gets wrong
};

// How a test was decided.
enum class SactDecision : std::uint8_t {
  kAxes,               // the staged axes
  kOuterSphereReject,  // bounding spheres disjoint: no overlap, no axis tested
  kInnerSphereAccept,  // inscribed spheres overlap: overlap, no axis tested
};

template <typename Scalar>
struct SactOptions {
  Scalar parallel_epsilon = Scalar(1e-6);  // unitless, added to |R_ij|; FCL, artifact
  // Cheap sphere tests before the axes: reject when the bounding spheres are
  // disjoint, accept when the inscribed spheres meet. Both are exact in real
  // arithmetic and carry a relative slack of 16 ulps against rounding.
  bool sphere_pretests = false;
  TranslationConvention convention = TranslationConvention::kBoxFrame;

  bool IsValid(std::string* error) const;
};

struct SactResult {
  std::int8_t separating_axis = kSactOverlap;  // 0..14, kSactOverlap or kSactSphereSeparated
  std::uint8_t axes_tested = 0;                // 0 (sphere-decided) .. 15
  SactDecision decided_by = SactDecision::kAxes;
  bool overlaps() const { return separating_axis == kSactOverlap; }
};

template <typename Scalar>
SactResult TestObbAabb(const Obb<Scalar>& obb, const Aabb<Scalar>& box, const SactOptions<Scalar>& options = {});

// The part of the pre-process that depends on the OBB alone (R = axes^T
// and |R| + epsilon), computed once for a query that a traversal tests
// against many boxes. TestPreparedObbAabb(PrepareSactObb(obb, options), box)
// runs the same operations in the same order as TestObbAabb(obb, box,
// options) (which is written as exactly that), so it returns the same result
// bit for bit; it only skips recomputing R and |R| at every node.
template <typename Scalar>
struct SactPreparedObb {
  Obb<Scalar> obb;
  Eigen::Matrix<Scalar, 3, 3> R;      // obb.axes^T
  Eigen::Matrix<Scalar, 3, 3> abs_r;  // |R_ij| + options.parallel_epsilon
  SactOptions<Scalar> options;
};

template <typename Scalar>
SactPreparedObb<Scalar> PrepareSactObb(const Obb<Scalar>& obb, const SactOptions<Scalar>& options = {}) {
  SactPreparedObb<Scalar> p;
  p.obb = obb;
  // B's axes are the world axes, so R_ij = A_i[j] exactly: R needs no
  // arithmetic at all, one reason the OBB/AABB test is more robust than the
  // general OBB/OBB test.
  p.R = obb.axes.transpose();
  p.abs_r = p.R.cwiseAbs().array() + options.parallel_epsilon;
  p.options = options;
  return p;
}

// The sphere pre-tests (options.sphere_pretests): a decision, or nullopt
// when the axes must decide.
template <typename Scalar>
std::optional<SactResult> SactSpherePretest(const Obb<Scalar>& obb, const Aabb<Scalar>& box);

// A = the OBB (centre a, axes A_i = columns, half extents ea), B = the AABB
// (centre b, axes = world x, y, z, half extents eb). Ericson 4.4.1 with
// R_ij = A_i . B_j and t = the translation in A's frame. Inline: a
// traversal calls it once per node.
template <typename Scalar>
[[gnu::always_inline]] inline SactResult TestPreparedObbAabb(const SactPreparedObb<Scalar>& p,
                                                             const Aabb<Scalar>& box) {
  using Vec3 = Eigen::Matrix<Scalar, 3, 1>;
  const SactOptions<Scalar>& options = p.options;
  if (options.sphere_pretests) {
    if (const auto decided = SactSpherePretest(p.obb, box)) return *decided;
  }
  const Vec3 d = box.centre - p.obb.centre;
  const auto& R = p.R;
  const Vec3 t = options.convention == TranslationConvention::kBoxFrame ? Vec3(R * d) : Vec3(p.obb.axes * d);
  const auto& abs_r = p.abs_r;
  const Vec3& ea = p.obb.half;
  const Vec3& eb = box.half;

  SactResult result;
  // Box-normal stage, A's axes: |t_i| against ea_i + sum_j eb_j |R_ij|.
  for (int i = 0; i < 3; ++i) {
    ++result.axes_tested;
    if (std::abs(t[i]) > ea[i] + eb.dot(abs_r.row(i).transpose())) {
      result.separating_axis = static_cast<std::int8_t>(i);
      return result;
    }
  }
  // Box-normal stage, B's axes. The translation along world axis j is d_j;
  // Ericson writes it as t . R_col(j), which is the same number after one
  // more rounding. The artifact's convention needs the rotated form to keep
  // its (wrong) t.
  const Vec3 t_b = options.convention == TranslationConvention::kBoxFrame ? d : Vec3(R.transpose() * t);
  for (int j = 0; j < 3; ++j) {
    ++result.axes_tested;
    if (std::abs(t_b[j]) > eb[j] + ea.dot(abs_r.col(j))) {
      result.separating_axis = static_cast<std::int8_t>(3 + j);
      return result;
    }
  }
  // Edge x edge stage: L = A_i x B_j; in A's frame L = e_i x R_col(j), so
  // t . L = t[i2] R[i1][j] - t[i1] R[i2][j], with (i, i1, i2) and (j, j1, j2)
  // cyclic (Ericson's nine unrolled cases, as one loop).
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      ++result.axes_tested;
      const Scalar ra = ea[i1] * abs_r(i2, j) + ea[i2] * abs_r(i1, j);
      const Scalar rb = eb[j1] * abs_r(i, j2) + eb[j2] * abs_r(i, j1);
      if (std::abs(t[i2] * R(i1, j) - t[i1] * R(i2, j)) > ra + rb) {
        result.separating_axis = static_cast<std::int8_t>(6 + 3 * i + j);
        return result;
      }
    }
  }
  return result;  // no axis separates: overlap (touching included)
}

// "A0".."A2", "B0".."B2", "A0xB0".."A2xB2"; "overlap", "sphere".
std::string SactAxisName(int axis);

// The stages one test executed.
enum class SactStage : std::uint8_t {
  kSpherePretest,  // not a datapath micro-op (no program runs it yet)
  kPreProcess,
  kBoxNormal,
  kEdgeEdge,
};
struct SactStageCounts {
  int sphere_pretests = 0;  // 0 or 1
  int pre_process = 0;      // 0 or 1
  int box_normal = 0;       // 0..6
  int edge_edge = 0;        // 0..9
};
SactStageCounts StagesOf(const SactResult& result, bool sphere_pretests);
// Appends the stages in execution order.
void AppendStages(const SactResult& result, bool sphere_pretests, std::vector<SactStage>& stages);
// Opcode::kPre / kBox / kEdge; nullopt for the sphere pre-test.
std::optional<Opcode> OpcodeOf(SactStage stage);

}  // namespace rc
