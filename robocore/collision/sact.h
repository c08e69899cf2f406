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
inline constexpr std::int8_t kSactOverlap = -1;            // "no axis separates"
inline constexpr std::int8_t kSactSphereSeparated = -2;    // outer sphere pre-test rejected

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
SactResult TestObbAabb(const Obb<Scalar>& obb, const Aabb<Scalar>& box,
                       const SactOptions<Scalar>& options = {});

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
