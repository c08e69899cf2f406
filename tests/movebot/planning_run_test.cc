// MoveBot planning: OMPL's RRTstar with the kernel-backed validity checks.
// Every returned path passes the independent exact check; best cost never
// increases; the same seed repeats; start/goal errors are reported; a tiny
// budget is never reported as success; an edge through an obstacle is
// rejected by both the motion validator and the independent check.
#include <cmath>

#include <gtest/gtest.h>

#include <ompl/base/spaces/RealVectorStateSpace.h>

#include "robocore/address_sample.h"
#include "support/test_data.h"
#include "workloads/movebot/arm_validity.h"
#include "workloads/movebot/movebot_run.h"
#include "workloads/movebot/path_verification.h"

#include <ompl/util/Console.h>

namespace rc {
namespace {

// OMPL's info messages would drown the test log.
const bool kQuietOmpl = [] {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  return true;
}();

constexpr ArmConfiguration kStart = {-1.3962634, 0, 0, 0, 0};  // RoWild's harness
constexpr ArmConfiguration kGoal = {0, 1.04719755, -1.30899694, -1.30899694, 0};

std::vector<Obbd> Boxes(const std::vector<Obstacle>& obstacles) {
  std::vector<Obbd> out;
  for (const Obstacle& o : obstacles) out.push_back(o.box);
  return out;
}

// A 8 cm block where the hand passes halfway along the straight
// joint-space edge from kStart to kGoal (the hand sweeps from (0.14, -0.36,
// 0.41) m to (0.46, 0, 0.43) m, through (0.36, -0.31, 0.46) m at 40%);
// start and goal are clear of it.
std::vector<Obstacle> BlockScene() {
  Obstacle block;
  block.box.centre = {0.38, -0.30, 0.46};
  block.box.half = {0.04, 0.04, 0.04};
  return {block};
}

ArmConfiguration Along(double t) {
  ArmConfiguration q;
  for (int j = 0; j < kArmJoints; ++j) q[j] = kStart[j] + t * (kGoal[j] - kStart[j]);
  return q;
}

MoveBotSettings FastSettings(std::uint64_t iterations, std::uint32_t seed) {
  MoveBotSettings s;
  s.start = kStart;
  s.goal = kGoal;
  s.iterations = iterations;
  s.batch_iterations = 50;
  s.motion_resolution_rad = 0.05;
  s.seed = seed;
  s.price_backends = false;
  return s;
}

TEST(MoveBotPlanning, LocobotScenePathsAreCollisionFreeAndCostNeverIncreases) {
  RC_REQUIRE_SHARED_DATA("movebot/locobot_obs.txt");
  const auto obstacles = ReadObstacleFile(test::SharedDataPath("movebot/locobot_obs.txt"));
  const ArmScene scene = ArmScene::FromObstacles(obstacles);
  const LocobotArm arm;
  for (std::uint32_t seed : {2u}) {  // exact within 2000 iterations (seeds 1, 3-5 need more)
    ArmCollisionChecker checker(arm, scene);
    MoveBotSettings settings = FastSettings(2000, seed);
    settings.batch_iterations = 250;
    settings.motion_resolution_rad = 0.02;  // the CLI's default; coarser grows the link boxes more
    const MoveBotResult r = RunMoveBot(checker, settings);
    ASSERT_EQ(r.status, MoveBotStatus::kExact) << "seed " << seed;
    EXPECT_EQ(r.iterations, 2000u);
    ASSERT_EQ(r.rows.size(), 8u);
    for (std::size_t i = 1; i < r.rows.size(); ++i)
      EXPECT_LE(r.rows[i].best_cost_rad, r.rows[i - 1].best_cost_rad) << "row " << i;
    EXPECT_NEAR(r.rows.back().best_cost_rad, r.path_cost_rad, 1e-9);
    // Never shorter than the straight line in joint space.
    double straight = 0;
    for (int j = 0; j < kArmJoints; ++j) straight += (kGoal[j] - kStart[j]) * (kGoal[j] - kStart[j]);
    EXPECT_GE(r.path_cost_rad, std::sqrt(straight) - 1e-9);
    const PathVerification v = VerifyPath(arm, Boxes(obstacles), r.path, 0.005);
    EXPECT_TRUE(v.ok) << v.message;
    EXPECT_GT(v.exact_tests, 0u);
    std::uint64_t queries = 0;
    for (const MoveBotRow& row : r.rows) queries += row.collision.queries;
    EXPECT_EQ(queries, checker.totals().queries);
    EXPECT_GT(queries, 400u);
  }
}

TEST(MoveBotPlanning, SameSeedSameTreeInOneProcess) {
  const auto obstacles = BlockScene();
  const ArmScene scene = ArmScene::FromObstacles(obstacles);
  const LocobotArm arm;
  ArmCollisionChecker a(arm, scene), b(arm, scene), c(arm, scene);
  const MoveBotResult ra = RunMoveBot(a, FastSettings(200, 5));
  const MoveBotResult rb = RunMoveBot(b, FastSettings(200, 5));
  const MoveBotResult rc = RunMoveBot(c, FastSettings(200, 6));
  ASSERT_EQ(ra.path.size(), rb.path.size());
  for (std::size_t i = 0; i < ra.path.size(); ++i) EXPECT_EQ(ra.path[i], rb.path[i]);
  EXPECT_EQ(a.totals().queries, b.totals().queries);
  EXPECT_NE(a.totals().queries, c.totals().queries);  // another seed, another tree
}

TEST(MoveBotPlanning, EdgeThroughTheBlockIsRejectedByValidatorAndIndependentCheck) {
  const auto obstacles = BlockScene();
  const ArmScene scene = ArmScene::FromObstacles(obstacles);
  const LocobotArm arm;
  ArmCollisionChecker checker(arm, scene);
  ASSERT_FALSE(checker.Collides(kStart));
  ASSERT_FALSE(checker.Collides(kGoal));
  // The straight edge: the independent check finds the collision...
  const PathVerification v = VerifyPath(arm, Boxes(obstacles), {kStart, kGoal}, 0.005);
  ASSERT_FALSE(v.ok);
  EXPECT_EQ(v.edge, 0);
  EXPECT_EQ(v.obstacle, 0);
  EXPECT_GT(v.t, 0.0);
  EXPECT_LT(v.t, 1.0);
  // ...and so does the kernel-backed motion validator.
  auto space = std::make_shared<ompl::base::RealVectorStateSpace>(kArmJoints);
  space->setBounds(-M_PI / 2, M_PI / 2);
  auto si = std::make_shared<ompl::base::SpaceInformation>(space);
  ArmMotionValidator validator(si, &checker, 0.02);
  ompl::base::State* s1 = si->allocState();
  ompl::base::State* s2 = si->allocState();
  for (int j = 0; j < kArmJoints; ++j) {
    s1->as<ompl::base::RealVectorStateSpace::StateType>()->values[j] = kStart[j];
    s2->as<ompl::base::RealVectorStateSpace::StateType>()->values[j] = kGoal[j];
  }
  EXPECT_FALSE(validator.checkMotion(s1, s2));
  std::pair<ompl::base::State*, double> last(si->allocState(), -1.0);
  EXPECT_FALSE(validator.checkMotion(s1, s2, last));
  EXPECT_GE(last.second, 0.0);
  EXPECT_LT(last.second, v.t);  // the last valid point lies before the first collision
  EXPECT_FALSE(checker.Collides(ToArmConfiguration(last.first)));
  si->freeState(s1);
  si->freeState(s2);
  si->freeState(last.first);
  // A planned path around it passes the same independent check.
  ArmCollisionChecker planning(arm, scene);
  const MoveBotResult r = RunMoveBot(planning, FastSettings(600, 3));
  ASSERT_EQ(r.status, MoveBotStatus::kExact);
  const PathVerification ok = VerifyPath(arm, Boxes(obstacles), r.path, 0.005);
  EXPECT_TRUE(ok.ok) << ok.message;
  EXPECT_GT(r.path.size(), 2u);
}

TEST(MoveBotPlanning, StartOrGoalInCollisionOrOutsideLimitsIsAnError) {
  const ArmScene scene = ArmScene::FromObstacles(BlockScene());
  const LocobotArm arm;
  ArmCollisionChecker checker(arm, scene);
  MoveBotSettings s = FastSettings(10, 1);
  s.goal = Along(0.4);  // the hand inside the block
  ASSERT_TRUE(checker.Collides(s.goal));
  try {
    RunMoveBot(checker, s);
    FAIL() << "accepted a goal in collision";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("goal"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("collision"), std::string::npos) << e.what();
  }
  s = FastSettings(10, 1);
  s.start[1] = 1.6;
  try {
    RunMoveBot(checker, s);
    FAIL() << "accepted a start outside the limits";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("joint 2"), std::string::npos) << e.what();
  }
}

TEST(MoveBotPlanning, TinyBudgetIsNeverReportedAsExact) {
  const ArmScene scene = ArmScene::FromObstacles(BlockScene());
  const LocobotArm arm;
  ArmCollisionChecker checker(arm, scene);
  MoveBotSettings s = FastSettings(1, 1);
  s.range_rad = 0.1;  // one step of 0.1 rad cannot reach a goal 2.7 rad away
  const MoveBotResult r = RunMoveBot(checker, s);
  EXPECT_NE(r.status, MoveBotStatus::kExact);
  if (r.status == MoveBotStatus::kApproximate) {
    EXPECT_GT(r.goal_distance_rad, 2.0);
    EXPECT_TRUE(VerifyPath(arm, Boxes(BlockScene()), r.path, 0.005).ok);
  }
  EXPECT_FALSE(std::isfinite(r.rows.back().best_cost_rad));
}

TEST(MoveBotPlanning, NoObstaclesPlansWithoutKernelQueries) {
  const ArmScene scene = ArmScene::FromObstacles({});
  const LocobotArm arm;
  ArmCollisionChecker checker(arm, scene, {}, SelfCollisionCheck::kOff);
  MoveBotSettings s = FastSettings(100, 1);
  s.price_backends = true;  // nothing to price: every row has no collision query
  const MoveBotResult r = RunMoveBot(checker, s);
  ASSERT_EQ(r.status, MoveBotStatus::kExact);
  EXPECT_EQ(checker.totals().queries, 0u);
  EXPECT_GT(checker.totals().configurations, 0u);
  double straight = 0;
  for (int j = 0; j < kArmJoints; ++j) straight += (kGoal[j] - kStart[j]) * (kGoal[j] - kStart[j]);
  EXPECT_GE(r.path_cost_rad, std::sqrt(straight) - 1e-9);
  EXPECT_LE(r.path_cost_rad, 1.6 * std::sqrt(straight));
  for (const MoveBotRow& row : r.rows) EXPECT_FALSE(row.collision_pricing.priced);
}

// With self-collision checked, the empty scene's only kernel work is the
// link pairs: a query per configuration, a node per pair tested, priced
// like any other.
TEST(MoveBotPlanning, NoObstaclesPricesTheLinkPairs) {
  const ArmScene scene = ArmScene::FromObstacles({});
  const LocobotArm arm;
  ArmCollisionChecker checker(arm, scene);
  MoveBotSettings s = FastSettings(100, 1);
  s.price_backends = true;
  const MoveBotResult r = RunMoveBot(checker, s);
  ASSERT_EQ(r.status, MoveBotStatus::kExact);
  const CollisionWorkCounters& totals = checker.totals();
  EXPECT_EQ(totals.queries, totals.configurations);
  EXPECT_EQ(totals.nodes, totals.self_tests);
  EXPECT_GE(totals.self_tests, totals.queries);
  for (const MoveBotRow& row : r.rows) {
    if (row.collision.queries == 0) continue;
    EXPECT_TRUE(row.collision_pricing.priced);
    EXPECT_EQ(row.collision_pricing.costs.front().queries, row.collision.queries);
  }
}

TEST(MoveBotPlanning, PricedRowsCarryEveryBackendsCycles) {
  const ArmScene scene = ArmScene::FromObstacles(BlockScene());
  const LocobotArm arm;
  ArmCollisionChecker checker(arm, scene);
  MoveBotSettings s = FastSettings(100, 2);
  s.price_backends = true;
  s.ledger.policy.kind = SchedulerKind::kAdaptive;
  const MoveBotResult r = RunMoveBot(checker, s);
  ASSERT_TRUE(r.priced);
  ASSERT_EQ(r.rows.size(), 2u);
  for (const MoveBotRow& row : r.rows) {
    ASSERT_TRUE(row.collision_pricing.priced);
    EXPECT_EQ(row.collision_pricing.costs.size(), r.collision_pricing.backends.size());
    for (const BatchCost& c : row.collision_pricing.costs) EXPECT_GT(c.cycles, 0u) << c.backend;
    EXPECT_EQ(row.collision_pricing.costs.front().queries, row.collision.queries);
  }
}

// The collision records take the ledger's address sample (--replay-sms,
// --replay-block-stride), as every workload's do: the sampled run says so
// and prices each backend within the sampled replay's stated error of the
// exact one (6%, tests/backends/sampled_pricing_test.cc), with identical
// queries. It once replayed every SM whatever the flags said.
TEST(MoveBotPlanning, CollisionRecordsTakeTheLedgersAddressSample) {
  // A tree of one box is priced alike by any sample: the LoCoBot scene's 15 nodes.
  RC_REQUIRE_SHARED_DATA("movebot/locobot_obs.txt");
  const ArmScene scene = ArmScene::FromObstacles(ReadObstacleFile(test::SharedDataPath("movebot/locobot_obs.txt")));
  const LocobotArm arm;
  MoveBotSettings sampled = FastSettings(500, 2);
  sampled.price_backends = true;
  sampled.ledger.replay_sms = kReplaySms;
  sampled.ledger.replay_block_stride = kReplayBlockStride;
  MoveBotSettings exact = sampled;
  exact.ledger.replay_sms = 0;
  ArmCollisionChecker a(arm, scene), b(arm, scene);
  const MoveBotResult rs = RunMoveBot(a, sampled);
  const MoveBotResult re = RunMoveBot(b, exact);
  EXPECT_EQ(rs.collision_pricing.replay_sms, kReplaySms);
  EXPECT_EQ(re.collision_pricing.replay_sms, 0);
  ASSERT_EQ(rs.collision_pricing.static_total_cycles.size(), re.collision_pricing.static_total_cycles.size());
  bool any_differs = false;
  for (std::size_t k = 0; k < re.collision_pricing.static_total_cycles.size(); ++k) {
    const double e = re.collision_pricing.static_total_cycles[k], v = rs.collision_pricing.static_total_cycles[k];
    EXPECT_NEAR(v, e, 0.06 * e) << rs.collision_pricing.backends[k];
    any_differs = any_differs || v != e;
  }
  EXPECT_TRUE(any_differs);  // the sample was replayed, not every SM
  EXPECT_EQ(a.totals().queries, b.totals().queries);
}

}  // namespace
}  // namespace rc

namespace rc {
namespace {

// The backend ball-query structures are exact, so stock RRTstar + GNAT and
// ours with P-Ray / P-Sphere grow the same tree on the same seed (the cost
// distributions over seeds are then equal; scripts/movebot_cost_study.py).
TEST(MoveBotPlanning, BackendNearestNeighboursGiveStockGnatsPath) {
  const ArmScene scene = ArmScene::FromObstacles(BlockScene());
  const LocobotArm arm;
  for (std::uint32_t seed : {1u, 4u}) {
    ArmCollisionChecker gnat_checker(arm, scene);
    const MoveBotResult gnat = RunMoveBot(gnat_checker, FastSettings(300, seed));
    for (NnKind kind : {NnKind::kPRay, NnKind::kPSphere}) {
      ArmCollisionChecker checker(arm, scene);
      MoveBotSettings s = FastSettings(300, seed);
      s.nn = kind;
      s.price_backends = true;
      const MoveBotResult r = RunMoveBot(checker, s);
      ASSERT_EQ(r.path.size(), gnat.path.size()) << ToString(kind) << " seed " << seed;
      for (std::size_t i = 0; i < r.path.size(); ++i) EXPECT_EQ(r.path[i], gnat.path[i]);
      EXPECT_EQ(checker.totals().queries, gnat_checker.totals().queries);
      for (const MoveBotRow& row : r.rows) {
        EXPECT_TRUE(row.nn.has_nodes);
        EXPECT_GT(row.nn.nodes_visited, 0u);
        ASSERT_TRUE(row.nn_pricing.priced);  // the NN kernel's record was priced
        EXPECT_EQ(row.nn_pricing.costs.front().queries, row.nn.queries);
      }
    }
  }
}

}  // namespace
}  // namespace rc
