// The median-split tree and its flat node array: structure, conservative
// bounds, the node layout, and traversal = brute force over all boxes
// (double and float, depth- and breadth-first), with queries placed at and
// near contact with the scene's boxes. Also the sphere robot.
#include <algorithm>
#include <set>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <omp.h>

#include "common/random_stream.h"
#include "pair_generator.h"
#include "robocore/collision/exact_overlap_reference.h"
#include "robocore/collision/sact_kernel_record.h"
#include "robocore/collision/sphere_robot.h"
#include "robocore/collision/tree_collision.h"
#include "scene_test_util.h"

namespace rc {
namespace {

using Vec3 = Eigen::Vector3d;

TEST(MedianSplitTree, StructureHoldsEveryBoxOnceUnderConservativeBounds) {
  const std::vector<Aabbd> boxes = test::RandomScene(300, 5);
  const BoxTree tree = BuildMedianSplitTree(boxes);
  ASSERT_EQ(tree.nodes.size(), 2 * boxes.size() - 1);
  EXPECT_EQ(tree.height(), 10u);  // ceil(log2 300) + 1
  test::ExpectWellFormed(tree);
}

TEST(MedianSplitTree, EmptyAndSingleBoxScenes) {
  const BoxTree empty = BuildMedianSplitTree({});
  EXPECT_TRUE(empty.nodes.empty());
  const FlatBoxTree<double> flat_empty(empty);
  EXPECT_FALSE(CollideObb(flat_empty, Obbd{}, CollisionOptions<double>{}).collides);
  EXPECT_EQ(CollideObb(flat_empty, Obbd{}, CollisionOptions<double>{}).last_exit, kNoNodeTested);
  const BoxTree one = BuildMedianSplitTree({Aabbd{Vec3(1, 0, 0), Vec3(0.5, 0.5, 0.5)}});
  ASSERT_EQ(one.nodes.size(), 1u);
  EXPECT_TRUE(one.nodes[0].is_leaf());
  const FlatBoxTree<double> flat(one);
  Obbd touching{Vec3(0, 0, 0), Eigen::Matrix3d::Identity(), Vec3(0.5, 0.1, 0.1)};
  const TraversalOutcome hit = CollideObb(flat, touching, CollisionOptions<double>{});
  EXPECT_TRUE(hit.collides);
  EXPECT_EQ(hit.colliding_box, 0u);
  EXPECT_EQ(hit.nodes_visited, 1u);
  EXPECT_THROW(BuildMedianSplitTree({Aabbd{Vec3::Zero(), Vec3(1, -1, 1)}}), std::invalid_argument);
}

TEST(FlatBoxTree, NodeLayoutAndConservativeInternalBoxes) {
  EXPECT_EQ(FlatBoxTree<float>::node_bytes(), 32u);
  EXPECT_EQ(FlatBoxTree<double>::node_bytes(), 64u);
  const BoxTree tree = BuildMedianSplitTree(test::RandomScene(200, 6));
  const FlatBoxTree<double> d(tree);
  const FlatBoxTree<float> f(tree);
  EXPECT_EQ(d.bytes(), 64u * tree.nodes.size());
  test::ExpectInternalBoxesContainTheirLeaves(d);
  test::ExpectInternalBoxesContainTheirLeaves(f);
  for (std::size_t i = 0; i < tree.nodes.size(); ++i) {
    if (!tree.nodes[i].is_leaf()) continue;
    const Aabbd& box = tree.boxes[tree.nodes[i].box];
    EXPECT_EQ(d.nodes()[i].first_child, tree.nodes[i].box);
    for (int j = 0; j < 3; ++j) {
      EXPECT_EQ(d.nodes()[i].centre[j], box.centre[j]);  // leaves are exact
      EXPECT_EQ(f.nodes()[i].half[j], static_cast<float>(box.half[j]));
    }
  }
}

template <typename Scalar>
void ExpectTreeEqualsBruteForce(const std::vector<Aabbd>& scene, std::uint64_t queries, std::uint64_t seed) {
  const FlatBoxTree<Scalar> flat(BuildMedianSplitTree(scene));
  CollisionOptions<Scalar> dfs, bfs;
  bfs.order = TraversalOrder::kBreadthFirst;
  std::uint64_t collisions = 0;
  for (std::uint64_t q = 0; q < queries; ++q) {
    const Obbd obb = test::SceneQuery(scene, seed, q);
    const Obb<Scalar> query = obb.template Cast<Scalar>();
    const bool brute = CollidesBruteForce(flat.boxes(), query, dfs.sact);
    const TraversalOutcome a = CollideObb(flat, query, dfs);
    const TraversalOutcome b = CollideObb(flat, query, bfs);
    ASSERT_EQ(a.collides, brute) << "query " << q;
    ASSERT_EQ(b.collides, brute) << "query " << q;
    if (brute) {
      EXPECT_TRUE(TestObbAabb(query, flat.boxes()[a.colliding_box], dfs.sact).overlaps());
    } else {
      EXPECT_EQ(a.nodes_visited, b.nodes_visited);  // the same nodes in another order
    }
    collisions += brute;
  }
  // Both answers must be well represented for the comparison to mean anything.
  EXPECT_GT(collisions, queries / 5);
  EXPECT_LT(collisions, queries * 4 / 5);
}

TEST(TreeTraversal, DoubleEqualsBruteForceIncludingContact) {
  ExpectTreeEqualsBruteForce<double>(test::RandomScene(300, 7), 20000, 8);
}

TEST(TreeTraversal, FloatEqualsFloatBruteForceIncludingContact) {
  ExpectTreeEqualsBruteForce<float>(test::RandomScene(300, 9), 20000, 10);
}

TEST(TreeTraversal, FarFromTheOrigin) {
  std::vector<Aabbd> scene = test::RandomScene(100, 11);
  for (Aabbd& b : scene) b.centre += Vec3(3e5, -7e5, 1e5);
  ExpectTreeEqualsBruteForce<double>(scene, 5000, 12);
  ExpectTreeEqualsBruteForce<float>(scene, 5000, 13);
}

// A record's exits tallied per query as robocore/exit_profile.h defines
// it: the passes without an exit first, then each exit in the order the
// query first met it. Written out here, independently of ExitTally.
ExitProfile TallyByHand(const KernelRecord& record) {
  ExitProfile profile;
  for (std::size_t q = 0; q < record.query_count(); ++q) {
    std::vector<std::uint8_t> order;
    std::vector<std::uint32_t> counts;
    std::uint32_t quiet = 0;
    for (std::uint32_t k = 0; k < record.nodes(q); ++k) {
      const std::uint8_t e = record.ExitAt(q, k);
      if (e == kNoExit) {
        ++quiet;
        continue;
      }
      const auto it = std::find(order.begin(), order.end(), e);
      if (it == order.end()) {
        order.push_back(e);
        counts.push_back(1);
      } else {
        ++counts[static_cast<std::size_t>(it - order.begin())];
      }
    }
    if (quiet > 0) {
      profile.variant.push_back(0);
      profile.passes.push_back(quiet);
    }
    for (std::size_t i = 0; i < order.size(); ++i) {
      profile.variant.push_back(static_cast<std::uint8_t>(1 + order[i]));
      profile.passes.push_back(counts[i]);
    }
    profile.offsets.push_back(static_cast<std::uint32_t>(profile.variant.size()));
  }
  return profile;
}

// CollideAnswers keeps no visit but gives CollideBatch's outcomes, OBB for
// OBB, in either traversal order.
TEST(TreeTraversal, AnswersAreTheBatchsOutcomes) {
  const std::vector<Aabbd> scene = test::RandomScene(80, 23);
  const FlatBoxTree<double> flat(BuildMedianSplitTree(scene));
  std::vector<Obbd> obbs;
  for (std::uint64_t q = 0; q < 500; ++q) obbs.push_back(test::SceneQuery(scene, 24, q));
  for (const TraversalOrder order : {TraversalOrder::kDepthFirst, TraversalOrder::kBreadthFirst}) {
    CollisionOptions<double> options;
    options.order = order;
    const CollisionBatch batch = CollideBatch(flat, obbs, options);
    const std::vector<TraversalOutcome> answers = CollideAnswers(flat, obbs, options);
    ASSERT_EQ(answers.size(), obbs.size());
    std::size_t collisions = 0;
    for (std::size_t q = 0; q < obbs.size(); ++q) {
      EXPECT_EQ(answers[q].collides, batch.outcomes[q].collides) << q;
      EXPECT_EQ(answers[q].nodes_visited, batch.outcomes[q].nodes_visited) << q;
      EXPECT_EQ(answers[q].last_exit, batch.outcomes[q].last_exit) << q;
      EXPECT_EQ(answers[q].colliding_box, batch.outcomes[q].colliding_box) << q;
      collisions += answers[q].collides;
    }
    EXPECT_GT(collisions, 0u);
    EXPECT_LT(collisions, obbs.size());
  }
}

// CollideBatchRecorded (the traversal and the record in one parallel pass)
// returns the outcomes CollideBatch returns and the record SactKernelRecord
// builds from that batch, array for array (its exits tallied), with every address kept, with
// one SM of 8 sampled and with every second block of it, at 1 and 2 threads
// (at one, the thread's lists become the record's arrays; at two, blocks
// are copied from both threads' lists).
TEST(TreeTraversal, RecordedBatchEqualsTheBatchsRecordAtAnyThreadCount) {
  const std::vector<Aabbd> scene = test::RandomScene(80, 21);
  const FlatBoxTree<double> flat(BuildMedianSplitTree(scene));
  std::vector<Obbd> obbs;
  for (std::uint64_t q = 0; q < 3000; ++q) obbs.push_back(test::SceneQuery(scene, 22, q));  // 12 blocks
  const CollisionOptions<double> options;
  const CollisionBatch batch = CollideBatch(flat, obbs, options, 0x2000);
  AddressSample sampled;
  sampled.sampled_sms = 1;
  AddressSample every_second_block = sampled;
  every_second_block.block_stride = 2;  // of SM 0's blocks 0 and 8, block 0
  const int threads = omp_get_max_threads();
  for (const AddressSample& sample : {AddressSample{}, sampled, every_second_block}) {
    const KernelRecord expected = SactKernelRecord(batch, nullptr, sample);
    for (const int t : {1, 2}) {
      omp_set_num_threads(t);
      std::vector<TraversalOutcome> outcomes;
      KernelRecord record;
      CollideBatchRecorded(flat, obbs, options, sample, &outcomes, &record, 0x2000);
      ASSERT_EQ(outcomes.size(), obbs.size());
      for (std::size_t q = 0; q < obbs.size(); ++q) {
        EXPECT_EQ(outcomes[q].collides, batch.outcomes[q].collides) << q;
        EXPECT_EQ(outcomes[q].nodes_visited, batch.outcomes[q].nodes_visited) << q;
        EXPECT_EQ(outcomes[q].colliding_box, batch.outcomes[q].colliding_box) << q;
      }
      EXPECT_EQ(record.fetch_offsets, expected.fetch_offsets) << t;
      // Exits tallied as the traversal ran, equal to the batch record's
      // exits tallied afterwards.
      EXPECT_TRUE(record.node_exits.empty()) << t;
      ASSERT_TRUE(record.exits_tallied()) << t;
      const ExitProfile tallied = TallyByHand(expected);
      EXPECT_EQ(record.tallied_exits->offsets, tallied.offsets) << t;
      EXPECT_EQ(record.tallied_exits->variant, tallied.variant) << t;
      EXPECT_EQ(record.tallied_exits->passes, tallied.passes) << t;
      EXPECT_NO_THROW(record.Validate());
      EXPECT_EQ(record.fetch_addresses, expected.fetch_addresses) << t;
      EXPECT_EQ(record.address_offsets, expected.address_offsets) << t;
      EXPECT_EQ(record.touched_sectors, expected.touched_sectors) << t;
      if (!sample.KeepsAll()) {  // every sector of every visited node, counted by hand
        std::set<std::uint64_t> sectors;
        for (const NodeVisit& v : batch.visits)
          for (std::uint64_t byte = batch.Address(v) - 0x2000; byte < batch.Address(v) - 0x2000 + batch.node_bytes; ++byte)
            sectors.insert(byte / static_cast<std::uint64_t>(sample.sector_bytes));
        EXPECT_EQ(record.touched_sectors, sectors.size()) << t;
      }
      EXPECT_EQ(record.node_bytes, expected.node_bytes);
      EXPECT_EQ(record.scalar_bytes, expected.scalar_bytes);
      EXPECT_EQ(record.step_kind, expected.step_kind);
      ASSERT_EQ(record.regions.size(), expected.regions.size());
      EXPECT_EQ(record.regions.front().base, expected.regions.front().base);
      EXPECT_EQ(record.regions.front().elements, expected.regions.front().elements);
    }
    EXPECT_EQ(sample.KeepsAll(), expected.address_offsets.empty());
  }
  omp_set_num_threads(threads);
}

TEST(TreeTraversal, BatchRecordsEveryFetch) {
  const std::vector<Aabbd> scene = test::RandomScene(50, 14);
  const FlatBoxTree<double> flat(BuildMedianSplitTree(scene));
  std::vector<Obbd> obbs;
  for (std::uint64_t q = 0; q < 200; ++q) obbs.push_back(test::SceneQuery(scene, 15, q));
  const CollisionBatch batch = CollideBatch(flat, obbs, CollisionOptions<double>{}, 0x1000);
  ASSERT_EQ(batch.query_count(), obbs.size());
  ASSERT_EQ(batch.visit_offsets.size(), obbs.size() + 1);
  EXPECT_EQ(batch.node_bytes, 64u);
  for (std::size_t q = 0; q < obbs.size(); ++q) {
    std::vector<NodeVisit> visits;
    const TraversalOutcome single = CollideObb(flat, obbs[q], CollisionOptions<double>{}, &visits);
    EXPECT_EQ(batch.outcomes[q].collides, single.collides);
    ASSERT_EQ(batch.visit_offsets[q + 1] - batch.visit_offsets[q], visits.size());
    EXPECT_EQ(batch.outcomes[q].nodes_visited, visits.size());
    EXPECT_EQ(visits.front().node, 0u);  // every query starts at the root
    for (std::size_t k = 0; k < visits.size(); ++k) {
      const NodeVisit& v = batch.visits[batch.visit_offsets[q] + k];
      EXPECT_EQ(v.node, visits[k].node);
      EXPECT_EQ(batch.Address(v), 0x1000u + 64u * v.node);
      // The recorded test is the SACT of that node's box.
      const SactResult r = TestObbAabb(obbs[q], flat.nodes()[v.node].box());
      EXPECT_EQ(v.exit, r.separating_axis);
      EXPECT_EQ(v.axes_tested, r.axes_tested);
    }
    EXPECT_EQ(batch.outcomes[q].last_exit, visits.back().exit);
  }
}

TEST(SphereRobot, SphereContainsTheObbAndTreeEqualsBruteForce) {
  const std::vector<Aabbd> scene = test::RandomScene(200, 16);
  const FlatBoxTree<double> flat(BuildMedianSplitTree(scene));
  std::vector<Obbd> obbs;
  RandomStream r(17, StreamPurpose::kTest, 0, 0);
  for (int q = 0; q < 3000; ++q) {  // generic placements: no contact within the epsilon band
    Obbd o;
    o.axes = Eigen::Quaterniond(r.Gaussian(), r.Gaussian(), r.Gaussian(), r.Gaussian()).normalized().toRotationMatrix();
    o.half = Vec3(r.Uniform(0.05, 0.6), r.Uniform(0.05, 0.3), r.Uniform(0.01, 0.2));
    o.centre = Vec3(r.Uniform(-1, 11), r.Uniform(-1, 11), r.Uniform(-1, 11));
    obbs.push_back(o);
    const Sphere<double> s = BoundingSphere(o);
    for (int corner = 0; corner < 8; ++corner) {  // in long double: the true corners
      Vec3ld offset = Vec3ld::Zero();
      for (int i = 0; i < 3; ++i)
        offset += ((corner >> i) & 1 ? 1.0L : -1.0L) * static_cast<long double>(o.half[i]) *
                  o.axes.col(i).cast<long double>();
      EXPECT_LE(offset.norm(), static_cast<long double>(s.radius));
    }
    bool brute = false;
    for (const Aabbd& b : scene) brute = brute || SphereOverlapsAabb(s, b);
    EXPECT_EQ(CollideSphere(flat, s, TraversalOrder::kDepthFirst).collides, brute);
  }
  const SphereRobotReport report = CompareSphereRobot(flat, obbs, CollisionOptions<double>{});
  std::printf(
      "[ sphere robot ] %zu queries: %zu OBB collisions, %zu sphere collisions, %zu false (%.1f%%), %zu missed\n",
      report.queries, report.obb_collisions, report.sphere_collisions, report.false_collisions,
      100 * report.false_collision_rate(), report.missed_collisions);
  EXPECT_EQ(report.missed_collisions, 0u);
  EXPECT_GT(report.false_collisions, 0u);
  EXPECT_EQ(report.sphere_collisions, report.obb_collisions + report.false_collisions);
}

}  // namespace
}  // namespace rc
