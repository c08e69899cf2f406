// Issue 5, "Backends agree": every backend (Backend::Names(), the cpu
// reference included) runs the collision kernel through Backend::
// RunCollisions and returns exactly the CPU reference's answers (collides,
// nodes visited, exit axis per query) on random OBBs against a box tree, a
// quadtree from an occupancy grid and an OctoMap octree.
//
// How the backends answer: as for ray casting (Backend::Run), the host
// kernel runs the traversal once and every backend prices the recorded
// work; no backend computes its own answer. So the test also checks what a
// backend prices is that same traversal: its query and node counts equal
// the reference's, and an RT unit makes one memory request per node fetch.
#include <tuple>

#include <gtest/gtest.h>
#include <octomap/OcTree.h>

#include "backends/backend.h"
#include "common/random_stream.h"
#include "robocore/collision/octree_from_octomap.h"
#include "robocore/collision/quadtree_from_grid.h"
#include "scene_test_util.h"

namespace rc {
namespace {

enum class SceneKind { kBoxTree, kQuadtree, kOctree };

const char* Name(SceneKind k) {
  return k == SceneKind::kBoxTree ? "box_tree" : k == SceneKind::kQuadtree ? "quadtree" : "octree";
}

BoxTree MakeScene(SceneKind kind) {
  switch (kind) {
    case SceneKind::kBoxTree: return BuildMedianSplitTree(test::RandomScene(150, 11));
    case SceneKind::kQuadtree: {
      OccupancyGrid grid(48, 40, 0.1);
      RandomStream r(12, StreamPurpose::kTest, 8, 0);
      for (int x = 0; x < grid.size_x(); ++x)
        for (int y = 0; y < grid.size_y(); ++y)
          grid.Set(x, y, r.Uniform() < 0.15 ? CellState::kOccupied : CellState::kFree);
      QuadtreeOptions options;
      options.z_max_m = 0.5;
      return BuildQuadtreeFromGrid(grid, options);
    }
    case SceneKind::kOctree: {
      octomap::OcTree tree(0.05);
      RandomStream r(13, StreamPurpose::kTest, 9, 0);
      for (int k = 0; k < 800; ++k)
        tree.updateNode(octomap::point3d(r.Uniform(0, 2), r.Uniform(-1, 1), r.Uniform(0, 1.5)), r.Uniform() < 0.8);
      tree.prune();
      return BuildOctreeFromOctoMap(tree);
    }
  }
  return {};
}

using Case = std::tuple<std::string, SceneKind>;
class CollisionBackendAgreement : public ::testing::TestWithParam<Case> {};

TEST_P(CollisionBackendAgreement, SameAnswersAsTheCpuReference) {
  const auto& [name, kind] = GetParam();
  const BoxTree scene = MakeScene(kind);
  ASSERT_FALSE(scene.boxes.empty());
  const FlatBoxTree<double> tree(scene);
  std::vector<Obbd> obbs;
  for (int q = 0; q < 300; ++q) obbs.push_back(test::SceneQuery(scene.boxes, 14, q));

  // The CPU reference: the kernel itself, and brute force over every box.
  const CollisionBatch reference = CollideBatch(tree, obbs, CollisionOptions<double>{});
  const auto backend = Backend::Create(name, BackendParameters{});
  std::vector<CollisionResult> results;
  const BatchCost cost = backend->RunCollisions(tree, obbs, results);
  ASSERT_EQ(results.size(), obbs.size());
  std::size_t collisions = 0, overlapping_visits = 0;
  for (std::size_t i = 0; i < obbs.size(); ++i) {
    const TraversalOutcome& ref = reference.outcomes[i];
    ASSERT_EQ(results[i].collides, ref.collides) << name << " query " << i;
    ASSERT_EQ(results[i].nodes_visited, ref.nodes_visited) << name << " query " << i;
    ASSERT_EQ(results[i].exit_axis, ref.last_exit) << name << " query " << i;
    ASSERT_EQ(results[i].collides, CollidesBruteForce(tree.boxes(), obbs[i], SactOptions<double>{})) << i;
    collisions += ref.collides;
  }
  for (const NodeVisit& v : reference.visits) overlapping_visits += v.overlaps();
  // Both answers occur, so a backend that always said one thing would fail.
  EXPECT_GT(collisions, obbs.size() / 10) << Name(kind);
  EXPECT_LT(collisions, obbs.size() * 9 / 10) << Name(kind);

  // What the backend priced is the reference traversal.
  EXPECT_EQ(cost.backend, name);
  EXPECT_EQ(cost.queries, obbs.size());
  EXPECT_EQ(cost.nodes, reference.visits.size());
  EXPECT_GT(cost.host_seconds, 0.0);
  EXPECT_EQ(cost.modelled, backend->specs().has_cost_model);
  if (!cost.modelled) return;
  EXPECT_GT(cost.cycles, cost.launch_cycles);
  EXPECT_GT(cost.energy_joules, 0.0);
  EXPECT_EQ(cost.memory.sector_requests, cost.memory.l1_hits + cost.memory.l2_accesses);
  if (backend->specs().has_rt_unit) {
    // Every sector of every node fetch: a 64-byte double node is two.
    EXPECT_EQ(cost.memory.sector_requests, cost.nodes * (tree.node_bytes() / 32));
    // The SACT program PUSHes only past its last axis: with an early exit
    // (a predicated-off PUSH does not count) that is once per overlapping
    // node; without one, once per node.
    const bool exits = backend->specs().early_exit != EarlyExitMode::kNone;
    EXPECT_EQ(cost.nodes_counted, exits ? overlapping_visits : cost.nodes) << name;
  }
}

INSTANTIATE_TEST_SUITE_P(EveryBackendEveryScene, CollisionBackendAgreement,
                         ::testing::Combine(::testing::ValuesIn(Backend::Names()),
                                            ::testing::Values(SceneKind::kBoxTree, SceneKind::kQuadtree,
                                                              SceneKind::kOctree)),
                         [](const auto& info) {
                           std::string name = std::get<0>(info.param) + "_" + Name(std::get<1>(info.param));
                           for (char& c : name)
                             if (c == '-') c = '_';
                           return name;
                         });

}  // namespace
}  // namespace rc
