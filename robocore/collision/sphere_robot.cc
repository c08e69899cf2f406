#include "robocore/collision/sphere_robot.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rc {

template <typename Scalar>
Sphere<Scalar> BoundingSphere(const Obb<Scalar>& obb) {
  // The farthest corner, from the axes as given (they may be orthonormal
  // only to within the input tolerance, so |half| alone could fall a few
  // ulps short), then 8 ulps up against the rounding of the norm.
  Scalar r = 0;
  for (int corner = 0; corner < 4; ++corner) {  // the other four are their mirror images
    Eigen::Matrix<Scalar, 3, 1> v = obb.half[0] * obb.axes.col(0);
    v += ((corner & 1) ? -obb.half[1] : obb.half[1]) * obb.axes.col(1);
    v += ((corner & 2) ? -obb.half[2] : obb.half[2]) * obb.axes.col(2);
    r = std::max(r, v.norm());
  }
  return Sphere<Scalar>{obb.centre, r * (1 + 8 * std::numeric_limits<Scalar>::epsilon())};
}

template <typename Scalar>
bool SphereOverlapsAabb(const Sphere<Scalar>& sphere, const Aabb<Scalar>& box) {
  const Eigen::Matrix<Scalar, 3, 1> outside =
      ((sphere.centre - box.centre).cwiseAbs() - box.half).cwiseMax(Scalar(0));
  return outside.squaredNorm() <= sphere.radius * sphere.radius;
}

template <typename Scalar>
TraversalOutcome CollideSphere(const FlatBoxTree<Scalar>& tree, const Sphere<Scalar>& sphere, TraversalOrder order,
                               std::vector<NodeVisit>* visits) {
  auto test = [&](const FlatNode<Scalar>& node) {
    NodeVisit v;
    v.exit = SphereOverlapsAabb(sphere, node.box()) ? kSactOverlap : kSactSphereSeparated;
    v.decided_by = v.overlaps() ? SactDecision::kInnerSphereAccept : SactDecision::kOuterSphereReject;
    return v;
  };
  return TraverseBoxTree(tree, order, test, visits);
}

template <typename Scalar>
SphereRobotReport CompareSphereRobot(const FlatBoxTree<Scalar>& tree, const std::vector<Obb<Scalar>>& obbs,
                                     const CollisionOptions<Scalar>& options) {
  SphereRobotReport report;
  for (const Obb<Scalar>& obb : obbs) {
    const TraversalOutcome exact = CollideObb(tree, obb, options);
    const TraversalOutcome sphere = CollideSphere(tree, BoundingSphere(obb), options.order);
    ++report.queries;
    report.obb_collisions += exact.collides;
    report.sphere_collisions += sphere.collides;
    report.false_collisions += sphere.collides && !exact.collides;
    report.missed_collisions += exact.collides && !sphere.collides;
    report.obb_nodes += exact.nodes_visited;
    report.sphere_nodes += sphere.nodes_visited;
  }
  return report;
}

#define RC_INSTANTIATE(Scalar)                                                                              \
  template Sphere<Scalar> BoundingSphere(const Obb<Scalar>&);                                               \
  template bool SphereOverlapsAabb(const Sphere<Scalar>&, const Aabb<Scalar>&);                             \
  template TraversalOutcome CollideSphere(const FlatBoxTree<Scalar>&, const Sphere<Scalar>&, TraversalOrder, \
                                          std::vector<NodeVisit>*);                                         \
  template SphereRobotReport CompareSphereRobot(const FlatBoxTree<Scalar>&, const std::vector<Obb<Scalar>>&, \
                                                const CollisionOptions<Scalar>&);
RC_INSTANTIATE(float)
RC_INSTANTIATE(double)
#undef RC_INSTANTIATE

}  // namespace rc
