// The RoboCore API's CheckCollisions (robocore_api.h): its results are
// CollideBatch's, its record is SactKernelRecord's, a bad configuration is
// rejected with a clear error, and every modelled backend prices the record.
#include <stdexcept>
#include <string>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "backends/backend.h"
#include "common/random_stream.h"
#include "robocore/collision/box_tree.h"
#include "robocore/collision/sact_kernel_record.h"
#include "robocore/micro_program.h"
#include "robocore/robocore_api.h"
#include "robocore/shipped_programs.h"

namespace rc {
namespace {

// 60 boxes in a 4 m room and 200 OBBs among them: about half collide.
struct Workload {
  FlatBoxTree<double> tree;
  std::vector<Obbd> obbs;
};

Workload MakeWorkload(std::uint64_t seed) {
  RandomStream r(seed, StreamPurpose::kTest, 7, 0);
  std::vector<Aabbd> boxes;
  for (int i = 0; i < 60; ++i) {
    Aabbd b;
    b.centre = Eigen::Vector3d(r.Uniform(0, 4), r.Uniform(0, 4), r.Uniform(0, 2));
    b.half = Eigen::Vector3d(r.Uniform(0.05, 0.3), r.Uniform(0.05, 0.3), r.Uniform(0.05, 0.3));
    boxes.push_back(b);
  }
  Workload w{FlatBoxTree<double>(BuildMedianSplitTree(boxes)), {}};
  for (int q = 0; q < 200; ++q) {
    Obbd o;
    o.axes = Eigen::Quaterniond(r.Gaussian(), r.Gaussian(), r.Gaussian(), r.Gaussian()).normalized().toRotationMatrix();
    o.centre = Eigen::Vector3d(r.Uniform(-0.5, 4.5), r.Uniform(-0.5, 4.5), r.Uniform(-0.5, 2.5));
    o.half = Eigen::Vector3d(r.Uniform(0.02, 0.4), r.Uniform(0.02, 0.2), r.Uniform(0.0, 0.1));
    w.obbs.push_back(o);
  }
  return w;
}

std::shared_ptr<const MicroProgram> Program(const std::string& text, const std::string& name = "test.asm") {
  return std::make_shared<const MicroProgram>(ParseMicroProgram(text, name));
}

void ExpectSameRecord(const KernelRecord& a, const KernelRecord& b) {
  EXPECT_EQ(a.step_kind, b.step_kind);
  EXPECT_EQ(a.program->name(), b.program->name());
  EXPECT_EQ(a.node_bytes, b.node_bytes);
  EXPECT_EQ(a.fetch_offsets, b.fetch_offsets);
  EXPECT_EQ(a.fetch_addresses, b.fetch_addresses);
  EXPECT_EQ(a.node_exits, b.node_exits);
  ASSERT_EQ(a.regions.size(), b.regions.size());
  EXPECT_EQ(a.regions[0].base, b.regions[0].base);
  EXPECT_EQ(a.regions[0].elements, b.regions[0].elements);
}

TEST(CheckCollisions, ResultsAreCollideBatchsAndTheRecordIsSactKernelRecords) {
  const Workload w = MakeWorkload(1);
  RoboCoreContext robocore;  // defaults: the shipped SACT program, no decode check
  std::vector<CollisionResult> results;
  KernelRecord record;
  robocore.CheckCollisions(w.obbs, w.tree, results, record);
  const CollisionBatch batch = CollideBatch(w.tree, w.obbs, CollisionOptions<double>{});
  ASSERT_EQ(results.size(), w.obbs.size());
  int collisions = 0;
  for (std::size_t i = 0; i < results.size(); ++i) {
    EXPECT_EQ(results[i].collides, batch.outcomes[i].collides) << i;
    EXPECT_EQ(results[i].nodes_visited, batch.outcomes[i].nodes_visited) << i;
    EXPECT_EQ(results[i].exit_axis, batch.outcomes[i].last_exit) << i;
    EXPECT_EQ(results[i].colliding_box, batch.outcomes[i].colliding_box) << i;
    collisions += results[i].collides;
  }
  EXPECT_GT(collisions, 20);
  EXPECT_LT(collisions, 180);
  ExpectSameRecord(record, SactKernelRecord(batch));
  EXPECT_EQ(record.regions[0].kind, FetchKind::kTreeNode);
  EXPECT_EQ(record.program->name(), "sact_obb_aabb");

  // The same with explicit configuration, float nodes and bfs.
  RoboCoreContext configured;
  configured.ConfigRoboCore(ShippedStepProgram(StepProgramKind::kSactTest));
  configured.ConfigDecode({{FetchKind::kTreeNode, 32}});
  const FlatBoxTree<float> tree_f(
      BuildMedianSplitTree(std::vector<Aabbd>(w.tree.boxes().begin(), w.tree.boxes().end())));
  std::vector<Obbf> obbs_f;
  for (const Obbd& o : w.obbs) obbs_f.push_back(o.Cast<float>());
  CollisionOptions<float> bfs;
  bfs.order = TraversalOrder::kBreadthFirst;
  configured.CheckCollisions(obbs_f, tree_f, results, record, bfs);
  const CollisionBatch batch_f = CollideBatch(tree_f, obbs_f, bfs);
  for (std::size_t i = 0; i < results.size(); ++i) EXPECT_EQ(results[i].collides, batch_f.outcomes[i].collides) << i;
  ExpectSameRecord(record, SactKernelRecord(batch_f));
  EXPECT_EQ(record.node_bytes, 32u);
}

// The batch CheckCollisions hands back is the one it ran: CollideBatch's,
// visit for visit, so a caller summarising the visits needs no second run.
TEST(CheckCollisions, HandsBackTheBatchItRan) {
  const Workload w = MakeWorkload(2);
  CollisionOptions<double> bfs;
  bfs.order = TraversalOrder::kBreadthFirst;
  std::vector<CollisionResult> results;
  KernelRecord record;
  CollisionBatch visits;
  RoboCoreContext().CheckCollisions(w.obbs, w.tree, results, record, bfs, &visits);
  const CollisionBatch want = CollideBatch(w.tree, w.obbs, bfs);
  EXPECT_EQ(visits.visit_offsets, want.visit_offsets);
  ASSERT_EQ(visits.visits.size(), want.visits.size());
  ASSERT_GT(visits.visits.size(), w.obbs.size());
  for (std::size_t k = 0; k < want.visits.size(); ++k) {
    EXPECT_EQ(visits.visits[k].node, want.visits[k].node) << k;
    EXPECT_EQ(visits.visits[k].exit, want.visits[k].exit) << k;
    EXPECT_EQ(visits.visits[k].axes_tested, want.visits[k].axes_tested) << k;
    EXPECT_EQ(visits.visits[k].decided_by, want.visits[k].decided_by) << k;
  }
  ASSERT_EQ(visits.outcomes.size(), want.outcomes.size());
  for (std::size_t i = 0; i < want.outcomes.size(); ++i) {
    EXPECT_EQ(visits.outcomes[i].collides, want.outcomes[i].collides) << i;
    EXPECT_EQ(visits.outcomes[i].nodes_visited, want.outcomes[i].nodes_visited) << i;
  }
  ExpectSameRecord(record, SactKernelRecord(visits));
}

TEST(CheckCollisions, RejectsAProgramWithoutASactSection) {
  const Workload w = MakeWorkload(2);
  std::vector<CollisionResult> results;
  KernelRecord record;
  RoboCoreContext robocore;
  robocore.ConfigRoboCore(ShippedStepProgram(StepProgramKind::kGridMarch));  // a valid ray program
  try {
    robocore.CheckCollisions(w.obbs, w.tree, results, record);
    FAIL() << "a ray program ran a collision batch";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("no SACT section"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(results.empty()) << "no partial output";
  // SACT micro-ops out of stage order are caught at configuration.
  std::string text = "loop:\n LOAD box, node\n PRE f, obb, box\n";
  for (int k = 0; k < 15; ++k)
    text += std::string(k < 6 ? " BOX s, f, " : " EDGE s, f, ") +
            std::to_string(k < 6 ? (k == 0   ? 1
                                    : k == 1 ? 0
                                             : k)
                                 : k - 6) +
            "\n RETURN_IF s\n";
  EXPECT_THROW(robocore.ConfigRoboCore(Program(text + " PUSH o\n")), std::invalid_argument);
  // A RETURN_IF before its axis is tested.
  EXPECT_THROW(robocore.ConfigRoboCore(Program("loop:\n LOAD box, node\n RETURN_IF s\n PRE f, obb, box\n"
                                               " BOX s, f, 0\n RETURN_IF s\n")),
               std::invalid_argument);
  // A SACT program cannot cast rays.
  robocore.ConfigRoboCore(ShippedStepProgram(StepProgramKind::kSactTest));
  std::vector<RayHit> hits;
  OccupancyGrid grid(4, 4, 0.1);
  RayBatch rays;
  EXPECT_THROW(robocore.ExecuteRoboCore(rays, RayCastScene(grid, RayCastMethod::kDda), hits, record),
               std::invalid_argument);
}

TEST(CheckCollisions, RejectsABadDecodeLayoutAndSpherePretests) {
  const Workload w = MakeWorkload(3);
  std::vector<CollisionResult> results;
  KernelRecord record;
  RoboCoreContext robocore;
  robocore.ConfigDecode({{FetchKind::kGridCell, 1}});
  EXPECT_THROW(robocore.CheckCollisions(w.obbs, w.tree, results, record), std::invalid_argument);
  robocore.ConfigDecode({{FetchKind::kTreeNode, 32}});  // the tree holds 64-byte double nodes
  try {
    robocore.CheckCollisions(w.obbs, w.tree, results, record);
    FAIL() << "a 32-byte layout decoded 64-byte nodes";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("64-byte"), std::string::npos) << e.what();
  }
  robocore.ConfigDecode({{FetchKind::kTreeNode, 64}});
  CollisionOptions<double> pretests;
  pretests.sact.sphere_pretests = true;
  EXPECT_THROW(robocore.CheckCollisions(w.obbs, w.tree, results, record, pretests), std::invalid_argument);
  CollisionOptions<double> bad;
  bad.sact.parallel_epsilon = -1;
  EXPECT_THROW(robocore.CheckCollisions(w.obbs, w.tree, results, record, bad), std::invalid_argument);
  EXPECT_TRUE(results.empty());
  robocore.CheckCollisions(w.obbs, w.tree, results, record);
  EXPECT_EQ(results.size(), w.obbs.size());
}

TEST(CheckCollisions, EveryBackendPricesTheRecord) {
  const Workload w = MakeWorkload(4);
  std::vector<CollisionResult> results;
  KernelRecord record;
  RoboCoreContext().CheckCollisions(w.obbs, w.tree, results, record);
  for (const std::string& name : Backend::Names()) {
    const auto backend = Backend::Create(name, BackendParameters{});
    const BatchCost cost = backend->Price(record);
    EXPECT_EQ(cost.backend, name);
    EXPECT_EQ(cost.queries, w.obbs.size()) << name;
    EXPECT_EQ(cost.nodes, record.total_nodes()) << name;
    if (!backend->specs().has_cost_model) continue;
    EXPECT_GT(cost.cycles, cost.launch_cycles) << name;
    EXPECT_GT(cost.energy_joules, 0.0) << name;
    if (backend->specs().has_sact_units) {
      EXPECT_GT(cost.ctrl_exits, 0u) << name;
    }
  }
}

}  // namespace
}  // namespace rc
