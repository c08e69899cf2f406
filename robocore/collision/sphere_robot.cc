#include "robocore/collision/sphere_robot.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

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
std::vector<Sphere<Scalar>> SphereCover(const Obb<Scalar>& obb, int spheres_per_obb) {
  if (spheres_per_obb < 1)
    throw std::invalid_argument("spheres per OBB: " + std::to_string(spheres_per_obb) + ", expected >= 1");
  if (spheres_per_obb == 1) return {BoundingSphere(obb)};
  int longest = 0;
  for (int j = 1; j < 3; ++j)
    if (obb.half[j] > obb.half[longest]) longest = j;
  const int n = spheres_per_obb;
  // Each slab is an OBB with the same axes, 1/n of the longest extent.
  Obb<Scalar> slab = obb;
  slab.half[longest] = obb.half[longest] / Scalar(n);
  std::vector<Sphere<Scalar>> cover;
  cover.reserve(n);
  for (int i = 0; i < n; ++i) {
    // Slab centres at -h + (2i + 1) h / n along the longest axis. The
    // division rounds, so the radius is taken from a slab grown by the
    // rounding of h / n (16 ulps of h) to keep the slabs overlapping.
    const Scalar offset = obb.half[longest] * (Scalar(2 * i + 1 - n) / Scalar(n));
    slab.centre = obb.centre + offset * obb.axes.col(longest);
    Obb<Scalar> grown = slab;
    grown.half[longest] += 16 * std::numeric_limits<Scalar>::epsilon() * obb.half[longest];
    cover.push_back(Sphere<Scalar>{slab.centre, BoundingSphere(grown).radius});
  }
  return cover;
}

template <typename Scalar>
bool SphereOverlapsAabb(const Sphere<Scalar>& sphere, const Aabb<Scalar>& box) {
  const Eigen::Matrix<Scalar, 3, 1> outside = ((sphere.centre - box.centre).cwiseAbs() - box.half).cwiseMax(Scalar(0));
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
SphereRobotBatch CollideSphereBatch(const FlatBoxTree<Scalar>& tree, const std::vector<Obb<Scalar>>& obbs,
                                    int spheres_per_obb, TraversalOrder order, std::uint64_t base_address) {
  SphereRobotBatch out;
  out.spheres_per_obb = spheres_per_obb;
  CollisionBatch& batch = out.spheres;
  batch.robot_model = CollisionRobotModel::kSpheres;
  batch.base_address = base_address;
  batch.node_bytes = tree.node_bytes();
  batch.scalar_bytes = sizeof(Scalar);
  batch.node_count = tree.nodes().size();
  batch.outcomes.reserve(obbs.size() * spheres_per_obb);
  out.obb_collides.reserve(obbs.size());
  for (const Obb<Scalar>& obb : obbs) {
    bool any = false;
    for (const Sphere<Scalar>& sphere : SphereCover(obb, spheres_per_obb)) {
      batch.outcomes.push_back(CollideSphere(tree, sphere, order, &batch.visits));
      batch.visit_offsets.push_back(batch.visits.size());
      any = any || batch.outcomes.back().collides;
    }
    out.obb_collides.push_back(any);
  }
  return out;
}

SphereRobotReport CompareSphereRobot(const SphereRobotBatch& spheres, const std::vector<TraversalOutcome>& exact) {
  if (exact.size() != spheres.obb_collides.size())
    throw std::invalid_argument("CompareSphereRobot: " + std::to_string(exact.size()) + " exact outcomes for " +
                                std::to_string(spheres.obb_collides.size()) + " OBBs");
  SphereRobotReport report;
  report.spheres_per_obb = spheres.spheres_per_obb;
  report.sphere_nodes = spheres.spheres.visits.size();
  for (std::size_t k = 0; k < exact.size(); ++k) {
    const bool sphere = spheres.obb_collides[k];
    ++report.queries;
    report.obb_collisions += exact[k].collides;
    report.sphere_collisions += sphere;
    report.false_collisions += sphere && !exact[k].collides;
    report.missed_collisions += exact[k].collides && !sphere;
    report.obb_nodes += exact[k].nodes_visited;
  }
  return report;
}

template <typename Scalar>
SphereRobotReport CompareSphereRobot(const FlatBoxTree<Scalar>& tree, const std::vector<Obb<Scalar>>& obbs,
                                     const CollisionOptions<Scalar>& options, int spheres_per_obb) {
  return CompareSphereRobot(CollideSphereBatch(tree, obbs, spheres_per_obb, options.order),
                            CollideAnswers(tree, obbs, options));
}

#define RC_INSTANTIATE(Scalar)                                                                                   \
  template Sphere<Scalar> BoundingSphere(const Obb<Scalar>&);                                                    \
  template std::vector<Sphere<Scalar>> SphereCover(const Obb<Scalar>&, int);                                     \
  template bool SphereOverlapsAabb(const Sphere<Scalar>&, const Aabb<Scalar>&);                                  \
  template SphereRobotBatch CollideSphereBatch(const FlatBoxTree<Scalar>&, const std::vector<Obb<Scalar>>&, int, \
                                               TraversalOrder, std::uint64_t);                                   \
  template TraversalOutcome CollideSphere(const FlatBoxTree<Scalar>&, const Sphere<Scalar>&, TraversalOrder,     \
                                          std::vector<NodeVisit>*);                                              \
  template SphereRobotReport CompareSphereRobot(const FlatBoxTree<Scalar>&, const std::vector<Obb<Scalar>>&,     \
                                                const CollisionOptions<Scalar>&, int);
RC_INSTANTIATE(float)
RC_INSTANTIATE(double)
#undef RC_INSTANTIATE

}  // namespace rc
