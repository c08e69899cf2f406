#pragma once
// The truth about one OBB/AABB pair, as cheaply as it can be established:
//   - a claimed separating axis is checked by projecting all 16 corners
//     onto it in long double (a separation certificate);
//   - a claimed overlap is checked by finding a point strictly inside both
//     boxes, by alternating projections onto the boxes shrunk by a margin
//     (a common-point certificate);
//   - when neither certificate holds (pairs near contact, or a wrong claim),
//     the exact linear-programming reference decides and gives the signed
//     depth s* (robocore/collision/exact_overlap_reference.h).
// None of this shares code with the SACT under test.
#include <cmath>
#include <limits>

#include "robocore/collision/exact_overlap_reference.h"
#include "robocore/collision/sact.h"

namespace rc::test {

enum class Verdict : std::uint8_t { kAxisCertificate, kPointCertificate, kLinearProgram };

struct Truth {
  bool overlaps = false;
  Verdict how = Verdict::kLinearProgram;
  long double depth = std::numeric_limits<long double>::quiet_NaN();  // s*, only from the LP
};

// The gap between the boxes' projections on axis k (SACT numbering; edge
// axes unnormalised, as the SACT uses them), from all 16 corners in long
// double: > 0 apart. `error` bounds its rounding; axis_l1 = |L|_1.
struct AxisGap {
  long double gap = 0;
  long double error = 0;
  long double axis_l1 = 0;
};
AxisGap GapOnAxis(const Obbd& obb, const Aabbd& box, int axis);
// True if axis k provably separates the boxes.
bool AxisSeparates(const Obbd& obb, const Aabbd& box, int axis);

// True if a claimed overlap of separated boxes is the epsilon's doing: on
// every one of the 15 axes the gap is at most epsilon x the half extents
// the SACT's epsilon multiplies there (sact.h), plus `rounding` x |L|_1.
bool EpsilonExplains(const Obbd& obb, const Aabbd& box, long double epsilon, long double rounding);
// True if a point strictly inside both boxes was found.
bool FindCommonPoint(const Obbd& obb, const Aabbd& box);

// The truth, using `claim` to pick the certificate to try first.
Truth Judge(const Obbd& obb, const Aabbd& box, const SactResult& claim);
// The truth with s*, always from the LP.
Truth JudgeExactly(const Obbd& obb, const Aabbd& box);

}  // namespace rc::test
