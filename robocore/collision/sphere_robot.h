#pragma once
// The sphere robot model (as CuRobo's collision spheres): each OBB covered
// by n spheres (n = 1: its bounding sphere; n > 1: n equal slabs along its
// longest axis, each in its own bounding sphere), and the OBB "collides"
// when any of its spheres overlaps the union of the boxes. Cheaper per node
// than a SACT (programs/sphere_aabb.asm: 9 micro-ops, no SACT unit), and
// never misses a collision the OBB has (the spheres contain the OBB), but it
// reports collisions the OBB does not have. The RoboGPU paper reports 10%
// false collisions from spheres; CompareSphereRobot measures the rate for a
// given robot and scene.
#include <cstdint>
#include <vector>

#include "robocore/collision/box_tree_traversal.h"
#include "robocore/collision/tree_collision.h"

namespace rc {

template <typename Scalar>
struct Sphere {
  Eigen::Matrix<Scalar, 3, 1> centre = Eigen::Matrix<Scalar, 3, 1>::Zero();  // m
  Scalar radius = 0;                                                         // m
};
using Sphered = Sphere<double>;
using Spheref = Sphere<float>;

// Centre = the OBB's; radius = distance to its farthest corner (|half
// extents| for orthonormal axes), rounded up so the sphere contains the OBB.
template <typename Scalar>
Sphere<Scalar> BoundingSphere(const Obb<Scalar>& obb);

// Closest point of the box to the centre within the radius (touching counts).
// n >= 1 spheres whose union contains the OBB: the OBB cut into n equal
// slabs across its longest axis, each slab's bounding sphere (as
// BoundingSphere; n = 1 is BoundingSphere). Throws std::invalid_argument
// for n < 1.
template <typename Scalar>
std::vector<Sphere<Scalar>> SphereCover(const Obb<Scalar>& obb, int spheres_per_obb);

template <typename Scalar>
bool SphereOverlapsAabb(const Sphere<Scalar>& sphere, const Aabb<Scalar>& box);

// A visit's exit is kSactOverlap or kSactSphereSeparated; decided_by names
// the sphere outcome (accept / reject), and no SACT stage ran.
template <typename Scalar>
TraversalOutcome CollideSphere(const FlatBoxTree<Scalar>& tree, const Sphere<Scalar>& sphere, TraversalOrder order,
                               std::vector<NodeVisit>* visits = nullptr);

// Every OBB's cover (SphereCover) as one query per sphere, OBB-major
// (query i = sphere i % n of OBB i / n), recorded as CollideBatch records
// (robot_model = kSpheres; sact_kernel_record.h prices it with the sphere
// program). obb_collides[k]: any sphere of OBB k collides.
struct SphereRobotBatch {
  CollisionBatch spheres;
  int spheres_per_obb = 1;
  std::vector<bool> obb_collides;
};
template <typename Scalar>
SphereRobotBatch CollideSphereBatch(const FlatBoxTree<Scalar>& tree, const std::vector<Obb<Scalar>>& obbs,
                                    int spheres_per_obb, TraversalOrder order,
                                    std::uint64_t base_address = kDefaultTreeBase);

struct SphereRobotReport {
  int spheres_per_obb = 1;
  std::size_t queries = 0;  // OBBs
  std::size_t obb_collisions = 0;
  std::size_t sphere_collisions = 0;
  std::size_t false_collisions = 0;   // sphere collides, OBB does not
  std::size_t missed_collisions = 0;  // OBB collides, sphere does not (0 unless within the SACT's epsilon band)
  std::uint64_t obb_nodes = 0;        // nodes visited by the OBB queries
  std::uint64_t sphere_nodes = 0;     // nodes visited by the sphere queries (all spheres)
  // False collisions over all queries, and over the OBB-collision-free ones.
  double false_collision_rate() const { return queries ? double(false_collisions) / queries : 0.0; }
  double false_rate_among_free() const {
    const std::size_t free = queries - obb_collisions;
    return free ? double(false_collisions) / free : 0.0;
  }
};

// The sphere robot against the exact SACT, both already run: `exact` holds
// one outcome per OBB of `spheres` (the SACT without sphere pre-tests), so
// a caller that has both batches compares them without running either
// kernel again. Throws std::invalid_argument if the counts disagree.
SphereRobotReport CompareSphereRobot(const SphereRobotBatch& spheres, const std::vector<TraversalOutcome>& exact);

// Runs both (CollideSphereBatch, then the SACT per OBB with `options`) and
// compares them.
template <typename Scalar>
SphereRobotReport CompareSphereRobot(const FlatBoxTree<Scalar>& tree, const std::vector<Obb<Scalar>>& obbs,
                                     const CollisionOptions<Scalar>& options, int spheres_per_obb = 1);

}  // namespace rc
