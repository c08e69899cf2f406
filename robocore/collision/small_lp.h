#pragma once
// A tiny dense linear-program solver in long double, written for the exact
// overlap reference (exact_overlap_reference.h): 4 free unknowns, a few
// inequality rows. Two independent methods:
//
//   MaximizeBySimplex             primal active-set simplex (Bland's rule: the
//                                 lowest-index leaving and entering rows, which
//                                 cannot cycle); about 10 pivots, ~20 us
//   MaximizeByVertexEnumeration   tries every basis of 4 rows and keeps the
//                                 best feasible vertex: no pivoting rules at
//                                 all, ~30x slower
//
// SolveSmallLp runs the simplex, checks its answer (primal feasibility and
// non-negative multipliers, i.e. the KKT conditions), and falls back to
// enumeration if the check fails, so the result never rests on the
// simplex's tolerances alone. Requirements: the rows' normals span R^4's
// first three axes together with the objective (no lines in the feasible
// set), the LP is bounded, and `start` is feasible.
#include <array>
#include <vector>

namespace rc {

inline constexpr int kLpUnknowns = 4;
using LpVector = std::array<long double, kLpUnknowns>;

struct LpRow {
  LpVector normal;  // row of M
  long double rhs;  // r
};

struct LpSolution {
  bool solved = false;
  LpVector z{};
  long double value = 0;    // c . z
  int pivots = 0;           // simplex pivots (0 for enumeration)
  bool enumerated = false;  // the fallback produced it
};

// maximize c . z subject to normal_k . z <= rhs_k for every row.
LpSolution MaximizeBySimplex(const std::vector<LpRow>& rows, const LpVector& c, const LpVector& start,
                             long double feasibility_tolerance);
LpSolution MaximizeByVertexEnumeration(const std::vector<LpRow>& rows, const LpVector& c,
                                       long double feasibility_tolerance);
LpSolution SolveSmallLp(const std::vector<LpRow>& rows, const LpVector& c, const LpVector& start,
                        long double feasibility_tolerance);

}  // namespace rc
