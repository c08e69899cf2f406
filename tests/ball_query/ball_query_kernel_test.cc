// The ball-query kernel itself: the tree stays shallow, early exit fetches
// fewer nodes than no early exit with identical answers (measured on 10^4
// 5-D states), the P-Sphere pop rule, and deterministic records.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "robocore/ball_query/ball_query_record.h"
#include "robocore/ball_query/ball_query_search.h"
#include "robocore/ball_query/ball_query_tree.h"

namespace rc {
namespace {

BallQueryTree RandomTree(std::size_t n, std::size_t count, std::uint64_t seed) {
  BallQueryTree tree(n);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-M_PI / 2, M_PI / 2);  // the arm's joint limits (rad)
  std::vector<double> p(n);
  for (std::size_t i = 0; i < count; ++i) {
    for (double& v : p) v = u(rng);
    tree.Insert(p.data());
  }
  return tree;
}

std::vector<std::vector<double>> RandomQueries(std::size_t n, std::size_t count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-M_PI / 2, M_PI / 2);
  std::vector<std::vector<double>> qs(count, std::vector<double>(n));
  for (auto& q : qs)
    for (double& v : q) v = u(rng);
  return qs;
}

TEST(BallQueryTree, StaysShallowAndRemovesCleanly) {
  BallQueryTree tree = RandomTree(5, 10000, 1);
  EXPECT_EQ(tree.size(), 10000u);
  EXPECT_GE(tree.rebuilds(), 10u);  // 8, 16, ..., 8192
  // Rebuilt at 8192, then 1808 incremental adds: still near log2(10^4) = 13.3.
  EXPECT_LE(tree.Depth(), 40);
  for (BallStateId id = 0; id < 10000; id += 2) tree.Remove(id);
  EXPECT_EQ(tree.size(), 5000u);
  EXPECT_FALSE(tree.IsLive(0));
  EXPECT_THROW(tree.Remove(0), std::invalid_argument);
  EXPECT_LE(tree.Depth(), 40);
  // Ids are reused lowest first.
  const double p[5] = {0, 0, 0, 0, 0};
  EXPECT_EQ(tree.Insert(p), 0u);
}

TEST(BallQueryTree, NodeBytesFollowTheDocumentedLayout) {
  EXPECT_EQ(BallQueryTree::NodeBytes(5), 168u);  // 2 children x (lo, hi) x 5 doubles + 2 uint32
  EXPECT_EQ(BallQueryTree::NodeBytes(1), 40u);
  EXPECT_THROW(BallQueryTree(0), std::invalid_argument);
}

// The paper's "6x fewer nodes with early exit" is RoboGPU's measurement on
// its data; this measures ours: same answers, fewer fetches.
TEST(BallQueryKernel, EarlyExitFetchesFewerNodesWithTheSameAnswers) {
  const BallQueryTree tree = RandomTree(5, 10000, 2);
  const auto queries = RandomQueries(5, 200, 3);
  for (BallQueryFormulation f : {BallQueryFormulation::kPSphere, BallQueryFormulation::kPRay}) {
    for (std::size_t k : {std::size_t{1}, std::size_t{10}}) {
      BallQueryConfig with, without;
      with.formulation = without.formulation = f;
      with.sphere_radius = without.sphere_radius = 1.0;  // rad; a 5-D unit ball holds about 170 of the 10^4 states
      without.early_exit = false;
      std::uint64_t nodes_with = 0, nodes_without = 0;
      std::vector<BallNeighbor> a, b;
      BallQueryVisits va, vb;
      for (const auto& q : queries) {
        BallNearestK(tree, with, q.data(), k, a, &va);
        BallNearestK(tree, without, q.data(), k, b, &vb);
        ASSERT_EQ(a.size(), b.size());
        for (std::size_t i = 0; i < a.size(); ++i) ASSERT_EQ(a[i].id, b[i].id);
        nodes_with += va.nodes.size();
        nodes_without += vb.nodes.size();
      }
      const double ratio = static_cast<double>(nodes_without) / static_cast<double>(nodes_with);
      RecordProperty(std::string(ToString(f)) + "_k" + std::to_string(k) + "_nodes_ratio", std::to_string(ratio));
      EXPECT_LT(nodes_with, nodes_without) << ToString(f) << " k = " << k;
      // k = 1 shrinks the radius from 1 rad to the nearest distance (about 0.35 rad here).
      if (k == 1) {
        EXPECT_GT(ratio, 1.5) << ToString(f);
      }
    }
  }
}

TEST(BallQueryKernel, PSphereFetchesFewerNodesThanPRay) {
  // The exact box distance prunes more than the grown-box slab test in 5-D,
  // and P-Sphere drops stale stack entries without a fetch.
  const BallQueryTree tree = RandomTree(5, 10000, 4);
  const auto queries = RandomQueries(5, 200, 5);
  BallQueryConfig sphere, ray;
  ray.formulation = BallQueryFormulation::kPRay;
  std::uint64_t nodes_sphere = 0, nodes_ray = 0;
  std::vector<BallNeighbor> out;
  BallQueryVisits v;
  for (const auto& q : queries) {
    BallNearestK(tree, sphere, q.data(), 10, out, &v);
    nodes_sphere += v.nodes.size();
    BallNearestK(tree, ray, q.data(), 10, out, &v);
    nodes_ray += v.nodes.size();
  }
  EXPECT_LT(nodes_sphere, nodes_ray);
}

TEST(BallQueryKernel, SmallFirstRadiusTakesMorePassesButTheSameAnswer) {
  const BallQueryTree tree = RandomTree(5, 2000, 6);
  const auto queries = RandomQueries(5, 20, 7);
  BallQueryConfig small, large;
  small.sphere_radius = 1e-3;
  large.sphere_radius = 10.0;
  std::vector<BallNeighbor> a, b;
  BallQueryVisits va, vb;
  for (const auto& q : queries) {
    BallNearestK(tree, small, q.data(), 5, a, &va);
    BallNearestK(tree, large, q.data(), 5, b, &vb);
    EXPECT_GT(va.passes, 1u);
    EXPECT_EQ(vb.passes, 1u);
    ASSERT_EQ(a.size(), 5u);
    for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i].id, b[i].id);
  }
}

TEST(BallQueryKernel, RadiusQueryEdgeCases) {
  const BallQueryTree tree = RandomTree(3, 100, 8);
  const double q[3] = {0, 0, 0};
  std::vector<BallNeighbor> out;
  BallQueryVisits v;
  BallWithinRadius(tree, BallQueryConfig{}, q, -1.0, out, &v);
  EXPECT_TRUE(out.empty());
  EXPECT_TRUE(v.nodes.empty()) << "a negative radius launches nothing";
  BallWithinRadius(tree, BallQueryConfig{}, q, std::nan(""), out, &v);
  EXPECT_TRUE(out.empty());
  BallWithinRadius(tree, BallQueryConfig{}, q, INFINITY, out, &v);
  EXPECT_EQ(out.size(), 100u);
  EXPECT_TRUE(std::is_sorted(out.begin(), out.end(),
                             [](const BallNeighbor& a, const BallNeighbor& b) { return a.distance < b.distance; }));
}

TEST(BallQueryRecorder, SameDataGivesTheSameRecord) {
  auto run = [] {
    const BallQueryTree tree = RandomTree(5, 3000, 9);
    BallQueryRecorder recorder(BallQueryFormulation::kPSphere, 5, std::uint64_t{1} << 32);
    std::vector<BallNeighbor> out;
    BallQueryVisits v;
    for (const auto& q : RandomQueries(5, 50, 10)) {
      BallNearestK(tree, BallQueryConfig{}, q.data(), 8, out, &v);
      recorder.AddQuery(v, tree.node_slots());
    }
    return recorder.Take();
  };
  const KernelRecord a = run(), b = run();
  EXPECT_EQ(a.query_count(), 50u);
  EXPECT_EQ(a.fetch_addresses, b.fetch_addresses);
  EXPECT_EQ(a.node_exits, b.node_exits);
  EXPECT_EQ(a.node_bytes, 168u);
  EXPECT_EQ(a.step_kind, StepProgramKind::kBallQueryPSphere);
  // Every exit is one of the program's: kNoExit, #0 or #1.
  for (std::uint8_t e : a.node_exits) EXPECT_TRUE(e == kNoExit || e <= kBallQueryNoState);
}

}  // namespace
}  // namespace rc
