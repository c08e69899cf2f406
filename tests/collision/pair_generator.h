#pragma once
// Random OBB/AABB pairs for the SACT property tests, deterministic per
// (seed, index). Half of them are built to sit at or near exact contact,
// where a separating-axis test goes wrong if it goes wrong at all:
//   kGeneric        random sizes, rotation and offset (most are far from contact)
//   kVertexVertex   a vertex of each box meets the other's along a random direction
//   kEdgeEdge       an edge of each box crosses the other's at their midpoints,
//                   along the edge x edge axis direction
//   kVertexOnFace   a vertex of one box on a face of the other
//   kParallel       OBB axes (anti)parallel to the world axes, about one world
//                   axis only, or rotated by 1e-12..1e-4 rad; face-to-face
// Each contact is moved apart or together by a gap of 0 (25%) or
// +-S x 10^U(-15, -1), S the pair's scale (log-uniform 1e-3..1e3 m). 10% of
// the pairs get a zero half extent, 25% are moved up to 10^6 S from the
// origin (both boxes by the same offset).
#include <cstdint>

#include "robocore/collision/aabb.h"
#include "robocore/collision/obb.h"

namespace rc::test {

enum class PairFamily : std::uint8_t { kGeneric, kVertexVertex, kEdgeEdge, kVertexOnFace, kParallel };
inline constexpr int kPairFamilyCount = 5;
const char* ToString(PairFamily family);

struct ObbAabbPair {
  Obbd obb;
  Aabbd box;
  PairFamily family = PairFamily::kGeneric;
  double gap = 0;    // m, the constructed gap (contact families); > 0 apart
  double scale = 1;  // m
};

ObbAabbPair GeneratePair(std::uint64_t seed, std::uint64_t index);

// An OBB of size ~obb_scale placed against `box` as a random family
// places it (generic: within 2.5 obb_scale of its centre), for scene tests.
Obbd ObbNearBox(const Aabbd& box, double obb_scale, std::uint64_t seed, std::uint64_t index);

}  // namespace rc::test
