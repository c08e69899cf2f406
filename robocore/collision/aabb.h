#pragma once
// An axis-aligned box as centre and half extents: the form the SACT and the
// flattened tree nodes use (the artifact's octree node stores its child
// boxes the same way, REFERENCE.md section 2).
//
// The box is the closed set { x : |x_j - centre_j| <= half_j }. A half
// extent may be 0 (a wall of zero thickness); never negative.
#include <Eigen/Core>

namespace rc {

template <typename Scalar>
struct Aabb {
  using Vec3 = Eigen::Matrix<Scalar, 3, 1>;

  Vec3 centre = Vec3::Zero();  // m
  Vec3 half = Vec3::Zero();    // m, >= 0

  template <typename To>
  Aabb<To> Cast() const {
    return Aabb<To>{centre.template cast<To>(), half.template cast<To>()};
  }
};

using Aabbd = Aabb<double>;
using Aabbf = Aabb<float>;

}  // namespace rc
