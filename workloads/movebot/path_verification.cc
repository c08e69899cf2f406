#include "workloads/movebot/path_verification.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "robocore/collision/exact_overlap_reference.h"

namespace rc {
namespace {

double Distance(const ArmConfiguration& a, const ArmConfiguration& b) {
  double s = 0;
  for (int j = 0; j < kArmJoints; ++j) s += (a[j] - b[j]) * (a[j] - b[j]);
  return std::sqrt(s);
}

bool Overlaps(const Obbd& link, const Obbd& obstacle, std::uint64_t* exact_tests) {
  const double reach = link.half.norm() + obstacle.half.norm();
  if ((link.centre - obstacle.centre).norm() > reach * (1 + 1e-9)) return false;
  Obbd local;  // the link box in the obstacle's frame
  local.centre = obstacle.axes.transpose() * (link.centre - obstacle.centre);
  local.axes = obstacle.axes.transpose() * link.axes;
  local.half = link.half;
  Aabbd box;
  box.centre = Eigen::Vector3d::Zero();
  box.half = obstacle.half;
  ++*exact_tests;
  return ExactObbAabbOverlap(local, box).overlaps();
}

}  // namespace

PathVerification VerifyPath(const LocobotArm& arm, const std::vector<Obbd>& obstacles,
                            const std::vector<ArmConfiguration>& path, double resolution_rad) {
  if (!(resolution_rad > 0) || !std::isfinite(resolution_rad))
    throw std::invalid_argument("verification resolution must be > 0 rad");
  PathVerification v;
  auto check = [&](const ArmConfiguration& q, long edge, double t) {
    ++v.configurations;
    std::string why;
    if (!arm.WithinLimits(q, &why)) {
      v = {false, v.configurations, v.exact_tests, edge, t, -1, -1, why};
      return false;
    }
    const auto links = arm.LinkObbs(q);
    for (int k = 0; k < kArmLinkBoxes; ++k)
      for (std::size_t o = 0; o < obstacles.size(); ++o)
        if (Overlaps(links[k], obstacles[o], &v.exact_tests)) {
          v = {false,
               v.configurations,
               v.exact_tests,
               edge,
               t,
               k,
               static_cast<long>(o),
               "link " + std::to_string(k) + " overlaps obstacle " + std::to_string(o) + " on edge " +
                   std::to_string(edge) + " at t = " + std::to_string(t)};
          return false;
        }
    return true;
  };
  if (path.empty()) return v;
  if (!check(path.front(), 0, 0.0)) return v;
  for (std::size_t e = 0; e + 1 < path.size(); ++e) {
    const ArmConfiguration& a = path[e];
    const ArmConfiguration& b = path[e + 1];
    const std::size_t n =
        std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(Distance(a, b) / resolution_rad)));
    for (std::size_t k = 1; k <= n; ++k) {
      const double t = static_cast<double>(k) / n;
      ArmConfiguration q;
      for (int j = 0; j < kArmJoints; ++j) q[j] = k == n ? b[j] : a[j] + t * (b[j] - a[j]);
      if (!check(q, static_cast<long>(e), t)) return v;
    }
  }
  return v;
}

}  // namespace rc
