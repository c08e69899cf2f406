#pragma once
// Self-collision: the arm's link boxes tested against each other, for the
// pairs its description lists (ArmDescription::self_collision_pairs).
//
// The second box of a pair is expressed in the first's frame, where the
// first is an axis-aligned box, and the two are tested with the collision
// kernel's own SACT (sact.h, with the checker's options): touching counts,
// and its epsilon errs toward overlap only, as against the scene. The
// independent check of a returned path (path_verification.h) tests the
// same pairs with the exact LP instead.
//
// A batch's pairs are collision-kernel work, priced with the scene's
// queries (SelfCollisionKernel): in the first box's frame the first box is
// an AABB centred at the origin with the link's half extents, which do not
// change with the configuration, so a pair is one SACT of the second box
// against a node holding that AABB. FindSelfCollision is the same search on
// the host, for a single configuration (a start or goal).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "robocore/collision/flat_box_tree.h"
#include "robocore/collision/obb.h"
#include "robocore/collision/sact.h"
#include "robocore/collision/tree_collision.h"
#include "workloads/movebot/locobot_arm.h"

namespace rc {

// Whether a check tests the link boxes against each other (RoWild's arm
// does not: kOff reproduces its problem).
enum class SelfCollisionCheck { kOn, kOff };

struct SelfCollision {
  int first = -1, second = -1;  // the first overlapping pair found (link box indices), -1 if none
  std::uint32_t tests = 0;      // pairs tested (the search stops at an overlap)
  bool found() const { return first >= 0; }
};

// The first of arm.self_collision_pairs, in their order, whose boxes among
// `links` overlap. With `growth_m` (one entry per pair, m; empty for none),
// each pair's second box is grown by its entry in every half extent first;
// any other size throws std::invalid_argument.
SelfCollision FindSelfCollision(const std::array<Obbd, kArmLinkBoxes>& links, const ArmDescription& arm,
                                const SactOptions<double>& options, const std::vector<double>& growth_m = {});

// The pairs as collision-kernel work: one query per configuration, a
// thread that tests its pairs in order, one node pass each, and stops at
// the first overlap, as a scene query stops at its first colliding leaf
// (the SACT program's loop runs per node and takes the query's box at its
// PRE, so on the RT units a pass prices the same whichever pair it tests).
// Not priced: the SIMT kernel sets a query's box up once, where a pair
// query sets up one per pair it tests, and no backend prices moving the
// second box into the first's frame (as none prices moving a link box into
// a rotated scene frame). A query per pair would price those set-ups but
// costs more to record and price than they are worth. Each link that
// is first in a pair has one node, a tree of its box in its own frame; the
// nodes follow the scene's in the device memory (from first_node on), so a
// batch of scene and pair queries is one recorded launch over one node
// array.
class SelfCollisionKernel {
 public:
  SelfCollisionKernel(const LocobotArm& arm, std::uint64_t first_node);

  std::uint64_t node_count() const { return trees_.size(); }

  // Appends one query to `batch` (whose node array must include these
  // nodes; none for an arm without pairs) and returns what
  // FindSelfCollision returns, bit for bit: the same SACT on the same boxes
  // in the same order, one visit per pair tested. `growth_m` as there. The
  // query's outcome names the overlapping pair's index as its box.
  // `pending`, if given, is the traversal's reusable list
  // (CollideObb's scratch), for a caller with many configurations.
  SelfCollision Collide(const std::array<Obbd, kArmLinkBoxes>& links, const CollisionOptions<double>& options,
                        const std::vector<double>& growth_m, CollisionBatch& batch,
                        std::vector<std::uint32_t>* pending = nullptr) const;

 private:
  std::vector<std::pair<int, int>> pairs_;
  std::array<int, kArmLinkBoxes> tree_of_link_;  // index into trees_, -1 for a link never first
  std::vector<FlatBoxTree<double>> trees_;
  std::uint64_t first_node_;
};

// Per pair of arm.self_collision_pairs, a bound (m/rad) on how far its
// second box moves relative to its first per joint-space distance along a
// straight line (LocobotArm::SweepRadius in the first box's frame). Times
// half a check spacing, the growth that makes one check cover its stretch
// of an edge.
std::vector<double> SelfSweepRadii(const LocobotArm& arm);

// "link 0 (upper arm) and link 3 (hand)": how messages name a pair.
std::string DescribeLinkPair(const ArmDescription& arm, int first, int second);

}  // namespace rc
