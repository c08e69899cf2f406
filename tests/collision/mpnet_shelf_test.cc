// The real robot OBBs (mpnet_master, 10 poses x 7 links) against the
// generated cubby-shelf scene: the tree's answers equal brute force and the
// exact union answer; nodes per query and the exit-axis distribution are
// printed (the real-OBB study); and the recorded batch maps onto the
// shipped SACT program's kernel record, which the backends price.
#include <cstdio>

#include <gtest/gtest.h>

#include "overlap_oracle.h"
#include "robocore/collision/box_csv.h"
#include "robocore/collision/collision_summary.h"
#include "robocore/collision/exact_overlap_reference.h"
#include "robocore/collision/shelf_scene.h"
#include "robocore/collision/sphere_robot.h"
#include "robocore/kernel_record.h"
#include "robocore/micro_op.h"
#include "robocore/shipped_programs.h"
#include "support/test_data.h"

namespace rc {
namespace {

const char* const kObbFile = "collision/mpnet_master_obb.csv";

std::vector<Obbd> RobotObbs() {
  std::vector<Obbd> obbs;
  for (const RobotObb& r : ReadObbCsv(test::SharedDataPath(kObbFile))) obbs.push_back(r.obb);
  return obbs;
}

void PrintStudy(const char* title, const CollisionSummary& s) {
  std::printf("[ %s ] %llu queries, %llu collisions, nodes per query mean %.2f max %u\n", title,
              (unsigned long long)s.queries, (unsigned long long)s.collisions, s.nodes_per_query_mean, s.nodes_max);
  std::printf("    nodes histogram:");
  for (const NodesHistogramBin& b : s.nodes_histogram)
    if (b.queries) std::printf(" [%u-%u] %llu", b.lo, b.hi, (unsigned long long)b.queries);
  std::printf("\n    node tests by exit:");
  for (int slot = 0; slot < kExitSlots; ++slot)
    if (s.node_test_exits[slot])
      std::printf(" %s %llu", SactAxisName(ExitOfSlot(slot)).c_str(), (unsigned long long)s.node_test_exits[slot]);
  std::printf("\n    stages: PRE %llu BOX %llu EDGE %llu\n", (unsigned long long)s.pre_process,
              (unsigned long long)s.box_normal, (unsigned long long)s.edge_edge);
}

TEST(MpnetShelf, TreeEqualsBruteForceAndTheExactUnion) {
  RC_REQUIRE_SHARED_DATA(kObbFile);
  const std::vector<Obbd> obbs = RobotObbs();
  const std::vector<Aabbd> scene = MakeShelfScene();
  const BoxTree tree = BuildMedianSplitTree(scene);
  const FlatBoxTree<double> flat(tree);
  const FlatBoxTree<float> flat_f(tree);
  CollisionOptions<double> dfs, bfs;
  bfs.order = TraversalOrder::kBreadthFirst;
  const CollisionBatch batch = CollideBatch(flat, obbs, dfs);
  const CollisionBatch batch_bfs = CollideBatch(flat, obbs, bfs);
  std::vector<Obbf> obbs_f;
  for (const Obbd& o : obbs) obbs_f.push_back(o.Cast<float>());
  const CollisionBatch batch_f = CollideBatch(flat_f, obbs_f, CollisionOptions<float>{});

  int exact_disagreements = 0, pair_disagreements = 0, collisions = 0;
  for (std::size_t q = 0; q < obbs.size(); ++q) {
    const bool brute = CollidesBruteForce(flat.boxes(), obbs[q], dfs.sact);
    EXPECT_EQ(batch.outcomes[q].collides, brute) << q;
    EXPECT_EQ(batch_bfs.outcomes[q].collides, brute) << q;
    EXPECT_EQ(batch_f.outcomes[q].collides, CollidesBruteForce(flat_f.boxes(), obbs_f[q], SactOptions<float>{})) << q;
    // Every OBB/box pair against the exact reference, and the union.
    bool exact_union = false;
    for (const Aabbd& b : scene) {
      const ExactOverlap exact = ExactObbAabbOverlap(obbs[q], b);
      exact_union = exact_union || exact.overlaps();
      if (TestObbAabb(obbs[q], b).overlaps() == exact.overlaps()) continue;
      ++pair_disagreements;
      EXPECT_TRUE(!exact.overlaps() && test::EpsilonExplains(obbs[q], b, 1e-6L, 1e-14L))
          << "query " << q << ": outside the band (s* = " << static_cast<double>(exact.depth) << ")";
    }
    exact_disagreements += exact_union != brute;
    collisions += brute;
  }
  std::printf(
      "[ mpnet x shelf ] %zu boxes, %zu nodes of %u B (artifact: 432 B); %d of %zu OBBs collide; "
      "vs the exact reference: %d of %zu OBB/box pairs and %d union answers differ (all in the epsilon band)\n",
      scene.size(), flat.nodes().size(), flat.node_bytes(), collisions, obbs.size(), pair_disagreements,
      obbs.size() * scene.size(), exact_disagreements);
  PrintStudy("dfs, double", Summarize(batch));
  PrintStudy("bfs, double", Summarize(batch_bfs));
  PrintStudy("dfs, float", Summarize(batch_f));
  const SphereRobotReport spheres = CompareSphereRobot(flat, obbs, dfs);
  std::printf(
      "[ sphere robot ] %zu false collisions of %zu queries (%.1f%%; %.1f%% of the collision-free), %zu missed\n",
      spheres.false_collisions, spheres.queries, 100 * spheres.false_collision_rate(),
      100 * spheres.false_rate_among_free(), spheres.missed_collisions);
  EXPECT_EQ(spheres.missed_collisions, 0u);
  // The scene is built to give both answers on these poses.
  EXPECT_GT(collisions, 5);
  EXPECT_LT(collisions, 65);
  // The artifact's convention gets real poses wrong, too.
  CollisionOptions<double> artifact;
  artifact.sact.convention = TranslationConvention::kArtifactRows;
  const CollisionBatch wrong = CollideBatch(flat, obbs, artifact);
  int differ = 0;
  for (std::size_t q = 0; q < obbs.size(); ++q) differ += wrong.outcomes[q].collides != batch.outcomes[q].collides;
  std::printf("[ artifact convention ] %d of %zu answers differ\n", differ, obbs.size());
  EXPECT_GT(differ, 0);
}

// The mapping tree_collision.h documents: one fetch per visit at
// Address(visit), node exit = the separating axis (RETURN_IF #k of
// programs/sact_obb_aabb.asm) or kNoExit for an overlap.
KernelRecord ToKernelRecord(const CollisionBatch& batch) {
  MemoryRegion region;
  region.name = "box tree nodes";
  region.kind = FetchKind::kGridCell;  // robocore has no tree-node kind yet; pricing uses only the bytes
  region.base = batch.base_address;
  region.element_bytes = batch.node_bytes;
  region.elements = batch.node_count;
  KernelRecordBuilder builder(ShippedStepProgram(StepProgramKind::kSactTest), StepProgramKind::kSactTest, region);
  for (std::size_t q = 0; q < batch.query_count(); ++q) {
    std::vector<std::uint64_t> addresses;
    std::vector<std::uint8_t> exits;
    for (std::uint64_t k = batch.visit_offsets[q]; k < batch.visit_offsets[q + 1]; ++k) {
      const NodeVisit& v = batch.visits[k];
      addresses.push_back(batch.Address(v));
      exits.push_back(v.exit >= 0 ? static_cast<std::uint8_t>(v.exit) : kNoExit);
    }
    builder.AddQuery(addresses, exits);
  }
  return builder.Build();
}

TEST(MpnetShelf, BatchMapsOntoTheShippedSactProgram) {
  RC_REQUIRE_SHARED_DATA(kObbFile);
  const FlatBoxTree<float> flat(BuildMedianSplitTree(MakeShelfScene()));
  std::vector<Obbf> obbs;
  for (const Obbd& o : RobotObbs()) obbs.push_back(o.Cast<float>());
  const CollisionBatch batch = CollideBatch(flat, obbs, CollisionOptions<float>{});
  const KernelRecord record = ToKernelRecord(batch);  // Build() validates addresses and exits
  EXPECT_EQ(record.query_count(), obbs.size());
  EXPECT_EQ(record.total_nodes(), batch.visits.size());
  EXPECT_EQ(record.node_bytes, 32u);
  EXPECT_EQ(record.program->ReturnIfCount(ProgramSection::kLoop), kSactAxisCount);
  // The TTA+ micro-ops of the recorded stages: a full test is 47 (paper).
  auto tta_ops = [](const SactResult& r) {
    std::vector<SactStage> stages;
    AppendStages(r, false, stages);
    std::size_t ops = 0;
    for (SactStage s : stages) ops += TtaPlusExpansion(*OpcodeOf(s)).size();
    return ops;
  };
  EXPECT_EQ(tta_ops(SactResult{kSactOverlap, kSactAxisCount, SactDecision::kAxes}), 47u);
  EXPECT_EQ(tta_ops(SactResult{0, 1, SactDecision::kAxes}), 5u + 4u);
  std::size_t total = 0;
  for (const NodeVisit& v : batch.visits) total += tta_ops(SactResult{v.exit, v.axes_tested, v.decided_by});
  std::printf("[ pricing input ] %zu node fetches of %u B, %zu TTA+ micro-ops for their SACT stages\n",
              batch.visits.size(), batch.node_bytes, total);
  EXPECT_GT(total, batch.visits.size() * 5);
}

}  // namespace
}  // namespace rc
