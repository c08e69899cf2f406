#pragma once
// The ball-query kernel: exact k-nearest and radius queries on a
// BallQueryTree, in the RoboGPU paper's two formulations (ball_query_config.h),
// with every node fetch recorded for the backends.
//
// Distance: the Euclidean distance on the coordinates, computed exactly as
// OMPL's RealVectorStateSpace::distance does (sum of squared differences in
// coordinate order, then sqrt), so answers equal NearestNeighborsLinear's
// bit for bit. Order: by (distance, insertion sequence) - ties go to the
// state inserted first, as NearestNeighborsLinear::nearest does.
//
// One pass with radius rho is a depth-first traversal from the root with a
// stack. Fetching a node tests both children against rho:
//   P-Sphere: squared Euclidean distance from the query to the child's box
//             <= rho^2; surviving internal children are pushed nearer first,
//             each with its squared distance;
//   P-Ray:    the query point lies in the child's box grown by rho on every
//             axis (the box of the spheres below it); surviving internal
//             children are pushed in stored order.
// A child that is a state is inside when its distance is <= rho; it is then
// offered to the best list. Box tests carry a relative margin of 1e-12, so
// rounding can only keep a node, never drop a state within rho.
//
// Early exit (config.early_exit), k-nearest only: once the best list holds
// k states, rho shrinks to the k-th best distance, and from then on
//   - a P-Sphere stack entry whose stored distance exceeds rho is dropped
//     when popped, without a fetch;
//   - children farther than rho (P-Sphere) or whose grown box misses the
//     query (P-Ray) are not pushed.
// The pass stops when the stack is empty. This is exact: a dropped node's
// box is farther than the k-th best distance, so no state in it can enter
// the list (a state at exactly that distance is still visited, and wins
// only on an earlier insertion sequence).
//
// Passes of a k-nearest query: the first runs with rho = config.sphere_radius.
// A pass that ends with min(k, size) states in the list is the answer (every
// state within its radius was considered). Otherwise the next pass runs with
// rho multiplied by config.radius_growth, from the root. A radius query is
// one pass with rho = its radius and no shrinking.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "robocore/ball_query/ball_query_config.h"
#include "robocore/ball_query/ball_query_tree.h"

namespace rc {

struct BallNeighbor {
  double distance = 0;         // Euclidean, as OMPL's RealVectorStateSpace
  std::uint64_t sequence = 0;  // the tie-break
  BallStateId id = 0;
};

// One query's node fetches, all passes, in order: node = device node index,
// exit = the RETURN_IF of the program that fired in that pass (kNoExit
// (0xFF) when a state went into the best list; see the .asm files).
struct BallQueryVisits {
  std::vector<std::uint32_t> nodes;
  std::vector<std::uint8_t> exits;
  std::uint32_t passes = 0;
  void clear() {
    nodes.clear();
    exits.clear();
    passes = 0;
  }
};

// Exit codes of the ball-query programs' loop.
inline constexpr std::uint8_t kBallQueryNoChild = 0;  // RETURN_IF #0: both children outside
inline constexpr std::uint8_t kBallQueryNoState = 1;  // RETURN_IF #1: no state inside

// The k nearest states, sorted by (distance, sequence); fewer when the tree
// holds fewer. `visits`, if given, is cleared and filled. The config must be
// valid (checked by the caller; BallQueryConfig::IsValid).
void BallNearestK(const BallQueryTree& tree, const BallQueryConfig& config, const double* query, std::size_t k,
                  std::vector<BallNeighbor>& out, BallQueryVisits* visits = nullptr);

// Every state with distance <= radius, sorted by (distance, sequence). A
// negative or NaN radius finds nothing and fetches nothing.
void BallWithinRadius(const BallQueryTree& tree, const BallQueryConfig& config, const double* query, double radius,
                      std::vector<BallNeighbor>& out, BallQueryVisits* visits = nullptr);

// OMPL's RealVectorStateSpace::distance on raw coordinates.
inline double EuclideanDistance(const double* a, const double* b, std::size_t n) {
  double sum = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double diff = a[i] - b[i];
    sum += diff * diff;
  }
  return std::sqrt(sum);
}

}  // namespace rc
