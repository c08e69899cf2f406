// The arm's self-collision: which link-box pairs are tested and why, the
// SACT's verdicts against the exact LP, and what the checker, the endpoint
// check, the independent path check and a planning run make of a folded
// arm, with the check on and off.
#include <cmath>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include <ompl/util/Console.h>

#include "robocore/collision/exact_overlap_reference.h"
#include "support/temp_dir.h"
#include "workloads/movebot/arm_collision_checker.h"
#include "workloads/movebot/arm_self_collision.h"
#include "workloads/movebot/movebot_report.h"
#include "workloads/movebot/movebot_run.h"
#include "workloads/movebot/obstacle_file.h"
#include "workloads/movebot/path_verification.h"

namespace rc {
namespace {

const bool kQuietOmpl = [] {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  return true;
}();

// Elbow and wrist pitch at +pi/2: the forearm points down and the wrist
// and hand fold back into the upper arm (both overlap it; the wrist's pair
// is listed first).
constexpr ArmConfiguration kFolded = {0, 0, M_PI / 2, M_PI / 2, 0};
constexpr ArmConfiguration kStretched = {0, 0, 0, 0, 0};

bool ExactOverlap(const Obbd& a, const Obbd& b) {
  Aabbd frame_box;
  frame_box.half = a.half;
  return ExactObbAabbOverlap(InFrameOf(b, a), frame_box).overlaps();
}

ArmConfiguration RandomConfiguration(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> joint(-M_PI / 2, M_PI / 2);
  ArmConfiguration q;
  for (double& v : q) v = joint(rng);
  return q;
}

// `from` moved `distance` (rad, joint-space) in a random direction (not
// clamped to the limits).
ArmConfiguration RandomStep(std::mt19937_64& rng, const ArmConfiguration& from, double distance) {
  std::normal_distribution<double> gauss;
  ArmConfiguration direction;
  double norm = 0;
  for (double& v : direction) {
    v = gauss(rng);
    norm += v * v;
  }
  ArmConfiguration to;
  for (int j = 0; j < kArmJoints; ++j) to[j] = from[j] + direction[j] * distance / std::sqrt(norm);
  return to;
}

TEST(ArmSelfCollision, PairsAreTheBoxesNotOnNeighbouringFramesWhoseVerdictNeverChanges) {
  const ArmDescription& d = LocobotArmDescription();
  const LocobotArm arm;
  std::mt19937_64 rng(7);
  for (int a = 0; a < kArmLinkBoxes; ++a)
    for (int b = a + 1; b < kArmLinkBoxes; ++b) {
      const bool neighbours = std::abs(d.links[a].frame - d.links[b].frame) <= 1;
      const bool listed = std::find(d.self_collision_pairs.begin(), d.self_collision_pairs.end(), std::pair{a, b}) !=
                          d.self_collision_pairs.end();
      EXPECT_EQ(listed, !neighbours) << a << "," << b;
      if (!neighbours) continue;
      // Why neighbours are left out: the verdict never depends on the
      // configuration. The upper arm and forearm, and the forearm and wrist,
      // overlap at their joint; the wrist and hand turn about their common
      // x axis 1 mm apart and never meet.
      const bool always = a < 2;
      for (int i = 0; i < 2000; ++i) {
        const auto links = arm.LinkObbs(RandomConfiguration(rng));
        ASSERT_EQ(ExactOverlap(links[a], links[b]), always) << "boxes " << a << " and " << b << ", sample " << i;
      }
    }
}

TEST(ArmSelfCollision, FoldedArmOverlapsItselfAndStretchedArmDoesNot) {
  const LocobotArm arm;
  const SelfCollision folded = FindSelfCollision(arm.LinkObbs(kFolded), arm.description(), {});
  ASSERT_TRUE(folded.found());
  EXPECT_EQ(folded.first, 0);   // the upper arm
  EXPECT_EQ(folded.second, 2);  // against the wrist, the first pair listed
  EXPECT_EQ(folded.tests, 1u);
  EXPECT_EQ(DescribeLinkPair(arm.description(), 0, 2), "link 0 (upper arm) and link 2 (wrist)");
  const SelfCollision stretched = FindSelfCollision(arm.LinkObbs(kStretched), arm.description(), {});
  EXPECT_FALSE(stretched.found());
  EXPECT_EQ(stretched.tests, arm.description().self_collision_pairs.size());
}

TEST(ArmSelfCollision, SactAgreesWithTheExactLpOnRandomConfigurations) {
  const LocobotArm arm;
  const ArmDescription& d = arm.description();
  std::mt19937_64 rng(11);
  int overlapping = 0, disagreements = 0;
  const int samples = 20000;
  for (int i = 0; i < samples; ++i) {
    const auto links = arm.LinkObbs(RandomConfiguration(rng));
    bool exact = false;
    for (const auto& [a, b] : d.self_collision_pairs) exact = exact || ExactOverlap(links[a], links[b]);
    const bool sact = FindSelfCollision(links, d, {}).found();
    overlapping += exact;
    // The SACT's epsilon may only err toward overlap, and at random
    // configurations a pair within its band is rarer than 1 in 20,000 (the
    // draws are libstdc++'s; no disagreement at this seed).
    EXPECT_FALSE(exact && !sact) << "the SACT separated overlapping links at sample " << i;
    disagreements += exact != sact;
  }
  EXPECT_EQ(disagreements, 0);
  // About 4% of the joint box self-collides (measured 4.4%): the test sees both verdicts.
  EXPECT_GT(overlapping, samples / 50);
  EXPECT_LT(overlapping, samples / 10);
}

TEST(ArmSelfCollision, CheckerCountsSelfCollisionsOnlyWhenAskedTo) {
  const ArmScene scene = ArmScene::FromObstacles({});
  const LocobotArm arm;
  ArmCollisionChecker on(arm, scene);
  EXPECT_TRUE(on.checks_self_collision());
  EXPECT_EQ(on.Collides(std::vector<ArmConfiguration>{kFolded, kStretched}), (std::vector<bool>{true, false}));
  const CollisionWorkCounters counted = on.TakeCounters();
  EXPECT_EQ(counted.configurations, 2u);
  // The folded arm stops at its first pair; the stretched one tests all.
  // Each configuration is one kernel query, a node per pair tested, and the
  // empty scene adds none.
  EXPECT_EQ(counted.self_tests, 1u + arm.description().self_collision_pairs.size());
  EXPECT_EQ(counted.queries, 2u);
  EXPECT_EQ(counted.nodes, counted.self_tests);
  EXPECT_EQ(counted.self_collisions, 1u);
  EXPECT_EQ(counted.self_only, 1u);  // the scene is empty
  EXPECT_EQ(on.SelfCollisionOf(kFolded).first, 0);

  ArmCollisionChecker off(arm, scene, {}, SelfCollisionCheck::kOff);
  EXPECT_FALSE(off.checks_self_collision());
  EXPECT_FALSE(off.Collides(kFolded));
  const CollisionWorkCounters off_counted = off.TakeCounters();
  EXPECT_EQ(off_counted.self_tests, 0u);
  EXPECT_EQ(off_counted.queries, 0u);
  EXPECT_EQ(off_counted.nodes, 0u);
  EXPECT_FALSE(off.SelfCollisionOf(kFolded).found());
}

// The kernel's query answers what the host's search does, grown or not:
// one query per configuration, one visit per pair tested, each a fetch of
// its first link's node, laid after the scene's nodes, and each visit's
// verdict that pair's own.
TEST(ArmSelfCollision, KernelQueryAnswersAsTheHostSearch) {
  const LocobotArm arm;
  const auto& pairs = arm.description().self_collision_pairs;
  const std::uint64_t scene_nodes = 15;
  const SelfCollisionKernel kernel(arm, scene_nodes);
  EXPECT_EQ(kernel.node_count(), 2u);  // links 0 and 1 are first in a pair
  CollisionBatch batch;
  batch.node_count = scene_nodes + kernel.node_count();
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> growth(0.0, 0.01);
  int found = 0;
  for (int i = 0; i < 4000; ++i) {
    const auto links = arm.LinkObbs(RandomConfiguration(rng));
    std::vector<double> grown;
    if (i % 2) grown = {growth(rng), growth(rng), growth(rng)};
    const SelfCollision host = FindSelfCollision(links, arm.description(), {}, grown);
    const std::size_t q = batch.query_count();
    const SelfCollision device = kernel.Collide(links, {}, grown, batch);
    ASSERT_EQ(device.first, host.first) << "configuration " << i;
    ASSERT_EQ(device.second, host.second) << "configuration " << i;
    ASSERT_EQ(device.tests, host.tests) << "configuration " << i;
    ASSERT_EQ(batch.query_count(), q + 1);
    EXPECT_EQ(batch.outcomes[q].collides, host.found());
    ASSERT_EQ(batch.visit_offsets[q + 1] - batch.visit_offsets[q], host.tests);
    EXPECT_EQ(batch.outcomes[q].nodes_visited, host.tests);
    // The outcome names the overlapping pair by its index, and ends with
    // the last pass's exit.
    EXPECT_EQ(batch.outcomes[q].colliding_box, host.found() ? host.tests - 1 : kNoBox);
    EXPECT_EQ(batch.outcomes[q].last_exit, batch.visits[batch.visit_offsets[q + 1] - 1].exit);
    for (std::size_t p = 0; p < host.tests; ++p) {
      const NodeVisit& visit = batch.visits[batch.visit_offsets[q] + p];
      EXPECT_EQ(visit.node, scene_nodes + (pairs[p].first == 0 ? 0 : 1));
      Aabbd frame_box;
      frame_box.half = links[pairs[p].first].half;
      Obbd moving = InFrameOf(links[pairs[p].second], links[pairs[p].first]);
      if (!grown.empty()) moving.half.array() += grown[p];
      const SactResult sact = TestObbAabb(moving, frame_box);
      EXPECT_EQ(visit.overlaps(), sact.overlaps());
      EXPECT_EQ(visit.exit, sact.separating_axis);
    }
    found += host.found();
  }
  EXPECT_GT(found, 100);  // both verdicts seen
  EXPECT_THROW(kernel.Collide(arm.LinkObbs(kFolded), {}, {0.1}, batch), std::invalid_argument);
}

// With the traversal's other options (breadth-first, sphere pre-tests) the
// kernel's query still answers as the host's search with the same options.
TEST(ArmSelfCollision, KernelQueryAnswersAsTheHostSearchWithEveryOption) {
  const LocobotArm arm;
  const SelfCollisionKernel kernel(arm, 0);
  CollisionOptions<double> breadth_first, pretests;
  breadth_first.order = TraversalOrder::kBreadthFirst;
  pretests.sact.sphere_pretests = true;
  std::mt19937_64 rng(19);
  for (const CollisionOptions<double>& options : {breadth_first, pretests}) {
    CollisionBatch batch;
    batch.node_count = kernel.node_count();
    std::vector<std::uint32_t> pending;
    int found = 0;
    for (int i = 0; i < 2000; ++i) {
      const auto links = arm.LinkObbs(RandomConfiguration(rng));
      const SelfCollision host = FindSelfCollision(links, arm.description(), options.sact);
      const SelfCollision device = kernel.Collide(links, options, {}, batch, &pending);
      ASSERT_EQ(device.first, host.first) << i;
      ASSERT_EQ(device.tests, host.tests) << i;
      found += host.found();
    }
    EXPECT_EQ(batch.visits.size(), batch.visit_offsets.back());
    EXPECT_GT(found, 20);
  }
}

// The checker lays the pair nodes after the scene's: a batch's node array
// is the scene's nodes and then two more, and every pair query fetches
// only those two; without the check, the scene's nodes alone.
TEST(ArmSelfCollision, CheckerLaysThePairNodesAfterTheScenes) {
  std::vector<Obstacle> obstacles(3);
  for (int k = 0; k < 3; ++k) {
    obstacles[k].box.centre = Eigen::Vector3d(2.0 + k, 2.0, 0.5);  // far from the arm
    obstacles[k].box.half = Eigen::Vector3d(0.1, 0.1, 0.1);
  }
  const ArmScene scene = ArmScene::FromObstacles(obstacles);
  const LocobotArm arm;
  ArmCollisionChecker on(arm, scene);
  const std::vector<ArmConfiguration> configurations = {kFolded, kStretched};
  on.Collides(configurations);
  const CollisionBatch work = on.TakeWork();
  EXPECT_EQ(work.node_count, scene.node_count() + 2);
  const std::size_t scene_queries = configurations.size() * kArmLinkBoxes * scene.frames().size();
  ASSERT_EQ(work.query_count(), scene_queries + configurations.size());
  for (std::size_t q = 0; q < work.query_count(); ++q)
    for (std::uint64_t k = work.visit_offsets[q]; k < work.visit_offsets[q + 1]; ++k) {
      const bool pair_node = work.visits[k].node >= scene.node_count();
      EXPECT_EQ(pair_node, q >= scene_queries) << "query " << q;
      EXPECT_LT(work.visits[k].node, work.node_count);
    }
  ArmCollisionChecker off(arm, scene, {}, SelfCollisionCheck::kOff);
  off.Collides(configurations);
  const CollisionBatch scene_only = off.TakeWork();
  EXPECT_EQ(scene_only.node_count, scene.node_count());
  EXPECT_EQ(scene_only.query_count(), scene_queries);
}

TEST(ArmSelfCollision, GrownBoxesOfAnEdgeCheckCoverTheLinksNearContact) {
  // A configuration just clear of self-contact: found by walking the wrist
  // pitch up from kStretched's side until the next step would overlap.
  const ArmScene scene = ArmScene::FromObstacles({});
  const LocobotArm arm;
  ArmCollisionChecker checker(arm, scene);
  ArmConfiguration q = {0, 0, M_PI / 2, -M_PI / 2, 0};
  ASSERT_FALSE(checker.Collides(q));
  while (!checker.Collides(ArmConfiguration{q[0], q[1], q[2], q[3] + 0.001, q[4]})) q[3] += 0.001;
  ASSERT_LT(q[3], 0.0);  // the wrist meets the upper arm on the way up from -pi/2
  EXPECT_FALSE(checker.Collides(q));
  // Grown by what the links sweep within 0.01 rad, the boxes reach the contact 0.001 rad away.
  EXPECT_TRUE(checker.Collides(std::vector<ArmConfiguration>{q}, 0.01).front());
}

TEST(ArmSelfCollision, SweepRadiusBoundsHowFarTheSecondBoxMovesInTheFirstsFrame) {
  const LocobotArm arm;
  const ArmDescription& d = arm.description();
  std::mt19937_64 rng(5);
  for (const auto& [a, b] : d.self_collision_pairs) {
    const double radius = arm.SweepRadius(b, d.links[a].frame);
    EXPECT_LT(radius, arm.SweepRadii()[b]);  // fewer joints than from the base
    double worst = 0;                        // largest displacement over radius x distance
    for (int i = 0; i < 3000; ++i) {
      const ArmConfiguration q = RandomConfiguration(rng);
      const double distance = 0.05;
      const ArmConfiguration moved = RandomStep(rng, q, distance);
      const auto before = arm.LinkObbs(q), after = arm.LinkObbs(moved);
      for (int corner = 0; corner < 8; ++corner) {
        Eigen::Vector3d p;
        for (int k = 0; k < 3; ++k) p[k] = (corner >> k & 1) ? d.links[b].size[k] / 2 : -d.links[b].size[k] / 2;
        // The corner in the first box's frame, before and after.
        const Obbd c0 = InFrameOf(before[b], before[a]), c1 = InFrameOf(after[b], after[a]);
        const double moved_m = ((c1.centre + c1.axes * p) - (c0.centre + c0.axes * p)).norm();
        worst = std::max(worst, moved_m / (radius * distance));
      }
    }
    EXPECT_LE(worst, 1.0) << "pair " << a << "," << b;
    EXPECT_GT(worst, 0.2) << "pair " << a << "," << b << ": a bound this loose would reject clear edges";
  }
}

TEST(ArmSelfCollision, AnEdgeTheGrownChecksAcceptIsClearAlongItsWholeLength) {
  // The motion validator's checks (arm_validity.cc) at 0.05 rad spacing,
  // each grown by what the links sweep within half a spacing, against the
  // exact LP every 0.0005 rad, on edges through and around the folded region.
  const ArmScene scene = ArmScene::FromObstacles({});
  const LocobotArm arm;
  ArmCollisionChecker checker(arm, scene);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> length(0.05, 0.6);
  int accepted = 0, rejected = 0;
  for (int e = 0; e < 400; ++e) {
    const ArmConfiguration a = RandomConfiguration(rng);
    const double l = length(rng);
    const ArmConfiguration b = RandomStep(rng, a, l);
    bool inside = true;
    for (int j = 0; j < kArmJoints; ++j) inside = inside && std::abs(b[j]) <= M_PI / 2;
    if (!inside) continue;
    const unsigned n = static_cast<unsigned>(std::ceil(l / 0.05));
    std::vector<ArmConfiguration> checks(n + 1);
    for (unsigned k = 0; k <= n; ++k)
      for (int j = 0; j < kArmJoints; ++j) checks[k][j] = a[j] + (b[j] - a[j]) * k / n;
    const std::vector<bool> hit = checker.Collides(checks, l / (2.0 * n));
    if (std::find(hit.begin(), hit.end(), true) != hit.end()) {
      ++rejected;
      continue;
    }
    ++accepted;
    const PathVerification v = VerifyPath(arm, {}, {a, b}, 0.0005);
    EXPECT_TRUE(v.ok) << "edge " << e << ": " << v.message;
  }
  EXPECT_GT(accepted, 100);
  EXPECT_GT(rejected, 5);
}

TEST(ArmSelfCollision, EdgeChecksGrowByTheJointsBetweenTheBoxesNotFromTheBase) {
  // Wrist pitched back with the elbow down: the hand clears the forearm by
  // a few cm. Grown by what the links sweep from the base within 0.03 rad
  // (3 cm for the hand, 2 cm for the forearm), the pair would meet; by
  // what the two wrist joints sweep (the hand alone, under 1 cm), it does
  // not.
  const ArmScene scene = ArmScene::FromObstacles({});
  const LocobotArm arm;
  ArmCollisionChecker checker(arm, scene);
  const ArmConfiguration q = {0, 0, 1.2, -1.2, 0};
  const double sweep_rad = 0.03;
  ASSERT_FALSE(checker.Collides(q));
  EXPECT_LT(SelfSweepRadii(arm)[2] * sweep_rad, 0.01);  // pair 2 is (forearm, hand)
  EXPECT_GT(arm.SweepRadii()[3] * sweep_rad, 0.025);
  EXPECT_FALSE(checker.Collides(std::vector<ArmConfiguration>{q}, sweep_rad).front());
  auto from_base = arm.LinkObbs(q);
  for (int k = 0; k < kArmLinkBoxes; ++k) from_base[k].half.array() += arm.SweepRadii()[k] * sweep_rad;
  const SelfCollision grown = FindSelfCollision(from_base, arm.description(), {});
  EXPECT_EQ(grown.first, 1);   // the forearm
  EXPECT_EQ(grown.second, 3);  // and the hand
  EXPECT_THROW(FindSelfCollision(arm.LinkObbs(q), arm.description(), {}, {0.01}), std::invalid_argument);
}

TEST(ArmSelfCollision, APairMustNameBoxesOnSuccessiveFrames) {
  ArmDescription d = LocobotArmDescription();
  d.self_collision_pairs = {{3, 0}};  // the hand's frame comes after the upper arm's: the sweep bound would be 0
  EXPECT_THROW(LocobotArm{d}, std::invalid_argument);
  d.self_collision_pairs = {{0, kArmLinkBoxes}};
  EXPECT_THROW(LocobotArm{d}, std::invalid_argument);
  d.self_collision_pairs = {{0, 3}};
  EXPECT_NO_THROW(LocobotArm{d});
}

TEST(ArmSelfCollision, AFoldedStartOrGoalIsItsOwnEndpointProblem) {
  const ArmScene scene = ArmScene::FromObstacles({});
  const LocobotArm arm;
  ArmCollisionChecker checker(arm, scene);
  std::string why;
  EXPECT_EQ(CheckEndpoint(checker, kFolded, &why), EndpointProblem::kSelfCollision);
  EXPECT_EQ(why, "in self-collision: link 0 (upper arm) and link 2 (wrist) overlap");
  ArmCollisionChecker off(arm, scene, {}, SelfCollisionCheck::kOff);
  EXPECT_EQ(CheckEndpoint(off, kFolded, &why), EndpointProblem::kNone);
}

TEST(ArmSelfCollision, IndependentCheckRejectsAPathThroughAFoldedArm) {
  const LocobotArm arm;
  const std::vector<ArmConfiguration> path = {kStretched, kFolded};
  const PathVerification v = VerifyPath(arm, {}, path, 0.01);
  ASSERT_FALSE(v.ok);
  EXPECT_EQ(v.edge, 0);
  EXPECT_EQ(v.link, 0);
  // On the way from stretched to folded, the hand reaches the upper arm first.
  EXPECT_EQ(v.other_link, 3);
  EXPECT_EQ(v.obstacle, -1);
  EXPECT_NE(v.message.find("link 0 (upper arm) and link 3 (hand) overlap"), std::string::npos) << v.message;
  EXPECT_GT(v.t, 0.0);
  EXPECT_TRUE(VerifyPath(arm, {}, path, 0.01, SelfCollisionCheck::kOff).ok);
}

TEST(ArmSelfCollision, PlannedStatesAndPathStayClearOfSelfCollision) {
  // No obstacles: only self-collision can reject a state. The goal lies
  // beside the folded region (the elbow down, the wrist pitched back).
  const ArmScene scene = ArmScene::FromObstacles({});
  const LocobotArm arm;
  ArmCollisionChecker checker(arm, scene);
  MoveBotSettings s;
  s.start = {-1.3962634, 0, 0, 0, 0};
  s.goal = {0, 0, M_PI / 2, -M_PI / 2, 0};
  s.iterations = 300;
  s.batch_iterations = 100;
  s.motion_resolution_rad = 0.05;
  s.price_backends = false;
  const MoveBotResult r = RunMoveBot(checker, s);
  EXPECT_TRUE(r.self_collision_checked);
  std::uint64_t self_collisions = 0;
  for (const MoveBotRow& row : r.rows) self_collisions += row.collision.self_collisions;
  EXPECT_GT(self_collisions, 0u);  // the planner met the folded region and was told
  ASSERT_EQ(r.status, MoveBotStatus::kExact);
  const PathVerification v = VerifyPath(arm, {}, r.path, 0.005);
  EXPECT_TRUE(v.ok) << v.message;

  // The timeline's self-collision columns are the rows' counts.
  const test::TempDir dir;
  WriteMoveBotTimeline(dir.Path("timeline.csv"), r);
  std::ifstream in(dir.Path("timeline.csv"));
  std::string line, cell;
  ASSERT_TRUE(std::getline(in, line));
  std::vector<std::string> header;
  for (std::istringstream fields(line); std::getline(fields, cell, ',');) header.push_back(cell);
  const auto column = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
  };
  const std::size_t tests_at = column("self_collision_tests"), refused_at = column("self_collisions");
  ASSERT_LT(tests_at, header.size());
  ASSERT_LT(refused_at, header.size());
  for (const MoveBotRow& row : r.rows) {
    ASSERT_TRUE(std::getline(in, line));
    std::vector<std::string> cells;
    for (std::istringstream fields(line); std::getline(fields, cell, ',');) cells.push_back(cell);
    ASSERT_LT(std::max(tests_at, refused_at), cells.size());
    EXPECT_EQ(cells[tests_at], std::to_string(row.collision.self_tests));
    EXPECT_EQ(cells[refused_at], std::to_string(row.collision.self_collisions));
  }
}

}  // namespace
}  // namespace rc
