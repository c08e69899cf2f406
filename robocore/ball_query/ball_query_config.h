#pragma once
// Options of the ball-query kernel (nearest-neighbour queries for MoveBot's
// RRT*) and its counters. The two formulations are the RoboGPU paper's
// (REFERENCE.md section 1, "ball query P-Sphere vs RTNN"):
//   P-Ray     the tree's states are spheres of radius rho and the query is a
//             ray: a zero-length probe at the query point, tested against the
//             box of the spheres under each child (a slab test) and then
//             against each state's sphere;
//   P-Sphere  the query is a sphere of radius rho over the states, tested
//             against each child's box by the exact Euclidean box distance,
//             nearer child first.
// Both return exactly the neighbours a brute-force search returns; they
// differ in the nodes they fetch and in the micro-ops per node
// (programs/ball_query_pray.asm, programs/ball_query_psphere.asm).
#include <cstdint>
#include <string>

namespace rc {

enum class BallQueryFormulation : std::uint8_t { kPRay, kPSphere };
const char* ToString(BallQueryFormulation formulation);  // "pray", "psphere"
// Accepts "pray" / "p-ray" / "psphere" / "p-sphere" (any case); throws
// std::invalid_argument naming the accepted values otherwise.
BallQueryFormulation ParseBallQueryFormulation(const std::string& text);

struct BallQueryConfig {
  BallQueryFormulation formulation = BallQueryFormulation::kPSphere;
  // Radius of the first pass of a k-nearest query, in the coordinates' unit
  // (rad for the arm's joint space). P-Ray: the states' sphere radius;
  // P-Sphere: the query sphere's radius. Range (0, inf).
  double sphere_radius = 0.5;
  // When a pass finds fewer than k states, the next pass runs with its
  // radius multiplied by this factor. Range (1, inf).
  double radius_growth = 2.0;
  // Early exit: once k states are found the radius shrinks to the k-th best
  // distance, so later nodes farther than it are skipped (exact; see
  // ball_query_search.h). Off: every node within the pass radius is
  // fetched (the no-early-exit baseline of the paper's "6x fewer nodes").
  bool early_exit = true;
  // Record every query's node fetches for the backends. The shipped programs
  // describe at most kMaxRecordedDimension coordinates per state.
  bool record = true;
  // Device byte address of the node array (away from 0 so a bad address
  // stands out; the value is not a cost).
  std::uint64_t base_address = std::uint64_t{1} << 32;

  // False with a message naming the field and its range.
  bool IsValid(std::string* error) const;
};

// Coordinates per state the shipped ball-query programs are written for
// (two vec3 passes per box; the arm uses 5).
inline constexpr std::size_t kMaxRecordedDimension = 6;

// What the queries since the counters were last reset did.
struct BallQueryCounters {
  std::uint64_t queries = 0;        // recorded queries (one per call that searched the tree)
  std::uint64_t nodes_visited = 0;  // node fetches, all passes
  std::uint64_t passes = 0;         // traversals (a k-nearest query may need more than one)
  double nodes_per_query() const {
    return queries == 0 ? 0.0 : static_cast<double>(nodes_visited) / static_cast<double>(queries);
  }
};

}  // namespace rc
