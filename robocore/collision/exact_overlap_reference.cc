#include "robocore/collision/exact_overlap_reference.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "robocore/collision/small_lp.h"

namespace rc {

std::vector<LpRow> OverlapLpRows(const Obbd& obb, const Aabbd& box) {
  // Unknowns: y = x - (OBB centre), relative to keep the numbers small, and s.
  Vec3ld offset;  // AABB centre - OBB centre
  for (int j = 0; j < 3; ++j)
    offset[j] = static_cast<long double>(box.centre[j]) - static_cast<long double>(obb.centre[j]);
  std::vector<LpRow> rows;
  rows.reserve(12);
  for (int i = 0; i < 3; ++i)  // OBB slab i: |A_i . y| <= half_i - s
    for (long double sign : {1.0L, -1.0L}) {
      LpRow row;
      for (int j = 0; j < 3; ++j) row.normal[j] = sign * static_cast<long double>(obb.axes(j, i));
      row.normal[3] = 1;
      row.rhs = obb.half[i];
      rows.push_back(row);
    }
  for (int j = 0; j < 3; ++j)  // AABB slab j: |y_j - offset_j| <= half_j - s
    for (long double sign : {1.0L, -1.0L}) {
      LpRow row;
      row.normal = {0, 0, 0, 1};
      row.normal[j] = sign;
      row.rhs = static_cast<long double>(box.half[j]) + sign * offset[j];
      rows.push_back(row);
    }
  return rows;
}

long double OverlapLpTolerance(const std::vector<LpRow>& rows) {
  long double scale = 0;
  for (const LpRow& row : rows) scale = std::max(scale, std::fabs(row.rhs));
  return 1e-14L * scale;
}

ExactOverlap ExactObbAabbOverlap(const Obbd& obb, const Aabbd& box) {
  const std::vector<LpRow> rows = OverlapLpRows(obb, box);
  // Feasible start: y = 0 (the OBB centre), s = the smallest right-hand side.
  LpVector start{0, 0, 0, rows.front().rhs};
  for (const LpRow& row : rows) start[3] = std::min(start[3], row.rhs);
  const LpSolution lp = SolveSmallLp(rows, {0, 0, 0, 1}, start, OverlapLpTolerance(rows));
  // Unreachable for valid boxes: the LP is bounded and has a vertex.
  if (!lp.solved) throw std::logic_error("exact overlap reference: LP not solved (invalid box?)");
  ExactOverlap out;
  out.depth = lp.z[3];
  for (int j = 0; j < 3; ++j) out.witness[j] = static_cast<long double>(obb.centre[j]) + lp.z[j];
  return out;
}

}  // namespace rc
