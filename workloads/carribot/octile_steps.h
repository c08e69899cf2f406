#pragma once
// The eight moves of an octile grid and their costs, in one fixed order that
// every CarriBot state space uses (it is part of the documented tie-breaking:
// successors are generated in this order).
#include <algorithm>
#include <array>
#include <cstdlib>

namespace rc {

inline constexpr double kSqrt2 = 1.41421356237309504880;

struct GridStep {
  int dx;
  int dy;
};

// Counter-clockwise from +x; odd indices are diagonals. The opposite of step
// d is (d + 4) % 8.
inline constexpr std::array<GridStep, 8> kOctileSteps = {
    {{1, 0}, {1, 1}, {0, 1}, {-1, 1}, {-1, 0}, {-1, -1}, {0, -1}, {1, -1}}};

inline constexpr bool IsDiagonalStep(int d) { return (d & 1) != 0; }
inline constexpr double OctileStepCost(int d) { return IsDiagonalStep(d) ? kSqrt2 : 1.0; }

// Shortest 8-connected distance on an empty grid, in cells: admissible and
// consistent for the costs above (corner-cutting rules only lengthen paths).
inline double OctileDistance(int dx, int dy) {
  const int ax = std::abs(dx), ay = std::abs(dy);
  const int lo = std::min(ax, ay), hi = std::max(ax, ay);
  return (hi - lo) + kSqrt2 * lo;
}

}  // namespace rc
