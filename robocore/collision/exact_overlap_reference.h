#pragma once
// An exact reference for "does this OBB overlap this AABB", derived
// independently of the separating-axis test (it shares no code with
// sact.cc, and uses no axes at all): a linear program over the boxes'
// half-spaces, solved in long double by enumerating its vertices.
//
// Each box is the intersection of three slabs, |n . (x - c)| <= h, so the
// pair has 12 half-spaces n_k . x <= r_k. The LP is
//
//     maximize s  over (x, s)  subject to  n_k . x + s <= r_k   (k = 1..12)
//
// i.e. the largest s such that both boxes, shrunk by s in every half extent,
// still share a point x. Its optimum s* ("signed depth", metres) answers
// the question and says how close the pair is to contact:
//   s* > 0   the boxes overlap with room to spare,
//   s* = 0   they touch,
//   s* < 0   they are apart; growing every half extent by -s* makes them touch.
// The feasible set in (x, s) has no lines (the slab normals span R^3), so
// the optimum sits at a vertex where 4 of the 12 constraints are active.
// small_lp.h solves it: a Bland's-rule simplex whose answer is checked
// (KKT), with enumeration of all C(12, 4) = 495 bases as the fallback.
// Tests run it on pairs near contact and use cheap certificates elsewhere.
//
// Accuracy: long double (64-bit mantissa) with a feasibility tolerance of
// 1e-14 x the problem's scale, so s* is good to about 1e-14 x (the larger of
// the half extents and the centre distance): far below the SACT's error
// bands (sact.h) that it is used to measure.
#include <vector>

#include <Eigen/Core>

#include "robocore/collision/aabb.h"
#include "robocore/collision/obb.h"
#include "robocore/collision/small_lp.h"

namespace rc {

using Vec3ld = Eigen::Matrix<long double, 3, 1>;

struct ExactOverlap {
  long double depth = 0;                        // s*, m (see above)
  Vec3ld witness = Vec3ld::Zero();              // m, world: a point of both boxes shrunk by s*
  bool overlaps() const { return depth >= 0; }  // touching counts
};

// The OBB's axes are taken as given; they should be orthonormal (the slab
// description and the corner description of the box agree only then).
ExactOverlap ExactObbAabbOverlap(const Obbd& obb, const Aabbd& box);

// The LP itself (rows over (x - OBB centre, s)) and its feasibility
// tolerance, so tests can solve it by both methods of small_lp.h.
std::vector<LpRow> OverlapLpRows(const Obbd& obb, const Aabbd& box);
long double OverlapLpTolerance(const std::vector<LpRow>& rows);

}  // namespace rc
