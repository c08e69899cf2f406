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
// These tests run on the host beside the kernel's batch: a few box-box
// tests per configuration, against the scene's trees' many nodes, and not
// priced on the backends (the summary prints both counts).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "robocore/collision/obb.h"
#include "robocore/collision/sact.h"
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

// Per pair of arm.self_collision_pairs, a bound (m/rad) on how far its
// second box moves relative to its first per joint-space distance along a
// straight line (LocobotArm::SweepRadius in the first box's frame). Times
// half a check spacing, the growth that makes one check cover its stretch
// of an edge.
std::vector<double> SelfSweepRadii(const LocobotArm& arm);

// "link 0 (upper arm) and link 3 (hand)": how messages name a pair.
std::string DescribeLinkPair(const ArmDescription& arm, int first, int second);

}  // namespace rc
