#include "workloads/movebot/path_verification.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "robocore/collision/exact_overlap_reference.h"

namespace rc {
namespace {

double Distance(const ArmConfiguration& a, const ArmConfiguration& b) {
  double s = 0;
  for (int j = 0; j < kArmJoints; ++j) s += (a[j] - b[j]) * (a[j] - b[j]);
  return std::sqrt(s);
}

// Whether `box` overlaps `other` (an obstacle or another link box), by the
// LP in other's frame.
bool Overlaps(const Obbd& box, const Obbd& other, std::uint64_t* exact_tests) {
  const double reach = box.half.norm() + other.half.norm();
  if ((box.centre - other.centre).norm() > reach * (1 + 1e-9)) return false;
  const Obbd local = InFrameOf(box, other);
  Aabbd other_box;
  other_box.centre = Eigen::Vector3d::Zero();
  other_box.half = other.half;
  ++*exact_tests;
  return ExactObbAabbOverlap(local, other_box).overlaps();
}

}  // namespace

PathVerification VerifyPath(const LocobotArm& arm, const std::vector<Obbd>& obstacles,
                            const std::vector<ArmConfiguration>& path, double resolution_rad, SelfCollisionCheck self) {
  if (!(resolution_rad > 0) || !std::isfinite(resolution_rad))
    throw std::invalid_argument("verification resolution must be > 0 rad");
  PathVerification v;
  // The first failure, at configuration `t` of edge `edge`.
  auto fail = [&](long edge, double t, int link, long obstacle, int other_link, std::string message) {
    v.ok = false;
    v.edge = edge;
    v.t = t;
    v.link = link;
    v.obstacle = obstacle;
    v.other_link = other_link;
    v.message = std::move(message);
    return false;
  };
  auto check = [&](const ArmConfiguration& q, long edge, double t) {
    ++v.configurations;
    std::string why;
    if (!arm.WithinLimits(q, &why)) return fail(edge, t, -1, -1, -1, why);
    const auto links = arm.LinkObbs(q);
    if (self == SelfCollisionCheck::kOn)
      for (const auto& [first, second] : arm.description().self_collision_pairs)
        if (Overlaps(links[second], links[first], &v.exact_tests))
          return fail(edge, t, first, -1, second,
                      DescribeLinkPair(arm.description(), first, second) + " overlap on edge " + std::to_string(edge) +
                          " at t = " + std::to_string(t));
    for (int k = 0; k < kArmLinkBoxes; ++k)
      for (std::size_t o = 0; o < obstacles.size(); ++o)
        if (Overlaps(links[k], obstacles[o], &v.exact_tests))
          return fail(edge, t, k, static_cast<long>(o), -1,
                      "link " + std::to_string(k) + " overlaps obstacle " + std::to_string(o) + " on edge " +
                          std::to_string(edge) + " at t = " + std::to_string(t));
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
