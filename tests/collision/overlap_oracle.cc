#include "overlap_oracle.h"

#include <algorithm>

#include <Eigen/Geometry>

namespace rc::test {
namespace {

using V = Vec3ld;

V Column(const Obbd& obb, int i) { return obb.axes.col(i).cast<long double>(); }

// The largest coordinate magnitude any corner can have: the scale of the
// rounding in long double sums over corners.
long double Magnitude(const Obbd& obb, const Aabbd& box) {
  const long double a = obb.centre.cwiseAbs().maxCoeff() + obb.half.sum();
  const long double b = box.centre.cwiseAbs().maxCoeff() + box.half.sum();
  return std::max(a, b);
}

V AxisVector(const Obbd& obb, int axis) {
  if (axis < 3) return Column(obb, axis);
  if (axis < 6) return V::Unit(axis - 3);
  const int i = (axis - 6) / 3, j = (axis - 6) % 3;
  return Column(obb, i).cross(V::Unit(j));
}

}  // namespace

AxisGap GapOnAxis(const Obbd& obb, const Aabbd& box, int axis) {
  const V l = AxisVector(obb, axis);
  long double min_a = INFINITY, max_a = -INFINITY, min_b = INFINITY, max_b = -INFINITY;
  for (int corner = 0; corner < 8; ++corner) {
    V pa = obb.centre.cast<long double>(), pb = box.centre.cast<long double>();
    for (int i = 0; i < 3; ++i) {
      const long double s = (corner >> i) & 1 ? 1.0L : -1.0L;
      pa += s * static_cast<long double>(obb.half[i]) * Column(obb, i);
      pb[i] += s * static_cast<long double>(box.half[i]);
    }
    const long double qa = l.dot(pa), qb = l.dot(pb);
    min_a = std::min(min_a, qa), max_a = std::max(max_a, qa);
    min_b = std::min(min_b, qb), max_b = std::max(max_b, qb);
  }
  // Each projection is good to a few long-double ulps of |l|_1 x magnitude;
  // 1e-17 is about 100 ulps.
  return AxisGap{std::max(min_b - max_a, min_a - max_b), 1e-17L * l.cwiseAbs().sum() * Magnitude(obb, box),
                 l.cwiseAbs().sum()};
}

bool AxisSeparates(const Obbd& obb, const Aabbd& box, int axis) {
  const AxisGap g = GapOnAxis(obb, box, axis);
  return g.gap > 2 * g.error;
}

bool EpsilonExplains(const Obbd& obb, const Aabbd& box, long double epsilon, long double rounding) {
  const Eigen::Matrix<long double, 3, 1> a = obb.half.cast<long double>(), b = box.half.cast<long double>();
  for (int axis = 0; axis < kSactAxisCount; ++axis) {
    // The half extents the epsilon multiplies on this axis (sact.cc's radii).
    long double widened;
    if (axis < 3) {
      widened = b.sum();
    } else if (axis < 6) {
      widened = a.sum();
    } else {
      const int i = (axis - 6) / 3, j = (axis - 6) % 3;
      widened = a[(i + 1) % 3] + a[(i + 2) % 3] + b[(j + 1) % 3] + b[(j + 2) % 3];
    }
    const AxisGap g = GapOnAxis(obb, box, axis);
    if (g.gap > epsilon * widened + rounding * g.axis_l1 + 2 * g.error) return false;
  }
  return true;
}

bool FindCommonPoint(const Obbd& obb, const Aabbd& box) {
  const long double err = 1e-17L * Magnitude(obb, box);
  // Shrink both boxes by a margin well above rounding, so a point found in
  // the shrunk boxes is strictly inside the real ones.
  const long double margin = 1e-9L * (obb.half.sum() + box.half.sum()) + 16 * err;
  V ha = obb.half.cast<long double>().array() - margin;
  V hb = box.half.cast<long double>().array() - margin;
  if (ha.minCoeff() < 0 || hb.minCoeff() < 0) return false;
  const V a = obb.centre.cast<long double>(), b = box.centre.cast<long double>();
  auto in_a = [&](const V& p) {
    for (int i = 0; i < 3; ++i)
      if (std::fabs(Column(obb, i).dot(p - a)) > ha[i] + margin / 2) return false;
    return true;
  };
  auto in_b = [&](const V& p) { return ((p - b).cwiseAbs() - hb).maxCoeff() <= margin / 2; };
  V p = (a + b) / 2;
  for (int iteration = 0; iteration < 48; ++iteration) {
    p = b + (p - b).cwiseMax(-hb).cwiseMin(hb);  // onto shrunk B
    if (in_a(p)) return true;
    V q = a;  // onto shrunk A
    for (int i = 0; i < 3; ++i) q += std::clamp(Column(obb, i).dot(p - a), -ha[i], ha[i]) * Column(obb, i);
    p = q;
    if (in_b(p)) return true;
  }
  return false;
}

Truth JudgeExactly(const Obbd& obb, const Aabbd& box) {
  const ExactOverlap exact = ExactObbAabbOverlap(obb, box);
  return Truth{exact.overlaps(), Verdict::kLinearProgram, exact.depth};
}

Truth Judge(const Obbd& obb, const Aabbd& box, const SactResult& claim) {
  // The claim's own certificate first, then the opposite one (a wrong
  // claim far from contact is cheap to refute), then the LP.
  auto any_axis = [&] {
    for (int axis = 0; axis < kSactAxisCount; ++axis)
      if (AxisSeparates(obb, box, axis)) return true;
    return false;
  };
  if (claim.overlaps()) {
    if (FindCommonPoint(obb, box)) return Truth{true, Verdict::kPointCertificate};
    if (any_axis()) return Truth{false, Verdict::kAxisCertificate};
  } else {
    const bool certified = claim.separating_axis >= 0 ? AxisSeparates(obb, box, claim.separating_axis) : any_axis();
    if (certified) return Truth{false, Verdict::kAxisCertificate};
    if (FindCommonPoint(obb, box)) return Truth{true, Verdict::kPointCertificate};
  }
  return JudgeExactly(obb, box);
}

}  // namespace rc::test
