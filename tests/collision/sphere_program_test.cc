// The sphere robot as a micro-op program (programs/sphere_aabb.asm): the
// program loads and keeps its exit contract, its records price on every
// backend beside the SACT's, the spheres are conservative (they never miss
// a collision the exact OBB answer has), and the false-collision rate is a
// measurement: random data here, the mpnet_master OBBs against the shelf
// when the shared data is present.
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <gtest/gtest.h>

#include "backends/backend.h"
#include "robocore/collision/box_csv.h"
#include "robocore/collision/exact_overlap_reference.h"
#include "robocore/collision/sact_kernel_record.h"
#include "robocore/collision/shelf_scene.h"
#include "robocore/collision/sphere_robot.h"
#include "robocore/micro_program.h"
#include "robocore/shipped_programs.h"
#include "scene_test_util.h"
#include "support/test_data.h"

namespace rc {
namespace {

TEST(SphereProgram, LoadsAndKeepsTheSphereExitContract) {
  const auto program = ShippedStepProgram(StepProgramKind::kSphereTest);
  EXPECT_EQ(program->name(), "sphere_aabb");
  std::string why;
  EXPECT_TRUE(KeepsSphereExitContract(*program, &why)) << why;
  EXPECT_FALSE(KeepsSactExitContract(*program, &why));
  EXPECT_EQ(program->ReturnIfCount(ProgramSection::kLoop), 1);
  // The file on disk parses to the embedded copy.
  const MicroProgram from_file = LoadMicroProgram(ShippedProgramDirectory() + "/sphere_aabb.asm");
  EXPECT_EQ(from_file.MicroOpCount(), program->MicroOpCount());
  // The SACT program is not a sphere program.
  EXPECT_FALSE(KeepsSphereExitContract(*ShippedStepProgram(StepProgramKind::kSactTest), &why));
}

TEST(SphereProgram, CoverContainsTheObb) {
  for (std::uint64_t q = 0; q < 200; ++q) {
    const Obbd obb = test::SceneQuery(test::RandomScene(20, 5), 6, q);
    for (int n : {1, 2, 3, 5}) {
      const std::vector<Sphered> cover = SphereCover(obb, n);
      ASSERT_EQ(cover.size(), static_cast<std::size_t>(n));
      // Every point of a 5x5x5 lattice over the OBB (corners included) lies
      // in some sphere.
      for (int i = 0; i < 125; ++i) {
        const Eigen::Vector3d u((i % 5) / 2.0 - 1, (i / 5 % 5) / 2.0 - 1, (i / 25) / 2.0 - 1);
        const Eigen::Vector3d p = obb.centre + obb.axes * u.cwiseProduct(obb.half);
        bool inside = false;
        // Up to the rounding of world coordinates (a few ulps of |p|).
        const double slack = 8 * std::numeric_limits<double>::epsilon() * p.norm();
        for (const Sphered& s : cover) inside = inside || (p - s.centre).norm() <= s.radius + slack;
        ASSERT_TRUE(inside) << "query " << q << ", n " << n << ", lattice point " << i;
      }
    }
  }
  EXPECT_THROW(SphereCover(Obbd{}, 0), std::invalid_argument);
}

// Spheres contain the OBB, so an OBB that (exactly) meets a box makes some
// sphere meet it: never "free" when the OBB collides. Against the SACT
// (CompareSphereRobot) a "miss" can only be one of the SACT's own false
// overlaps in its epsilon band at contact (sact.h); half of these queries
// are built at contact, so some occur, and each must be one.
TEST(SphereProgram, SpheresAreConservativeAndTheFalseRateIsMeasured) {
  const std::vector<Aabbd> scene = test::RandomScene(120, 21);
  const FlatBoxTree<double> tree(BuildMedianSplitTree(scene));
  std::vector<Obbd> obbs;
  for (int q = 0; q < 600; ++q) obbs.push_back(test::SceneQuery(scene, 22, q));
  const CollisionBatch sact = CollideBatch(tree, obbs, CollisionOptions<double>{});
  for (int n : {1, 4}) {
    const SphereRobotBatch spheres = CollideSphereBatch(tree, obbs, n, TraversalOrder::kDepthFirst);
    ASSERT_EQ(spheres.spheres.query_count(), obbs.size() * n);
    std::size_t exact_collisions = 0, false_collisions = 0, sact_band_misses = 0;
    for (std::size_t k = 0; k < obbs.size(); ++k) {
      bool exact = false;
      for (const Aabbd& b : scene) exact = exact || ExactObbAabbOverlap(obbs[k], b).overlaps();
      if (exact) {
        EXPECT_TRUE(spheres.obb_collides[k]) << "spheres miss a collision: OBB " << k << ", n " << n;
      }
      exact_collisions += exact;
      false_collisions += spheres.obb_collides[k] && !exact;
      if (sact.outcomes[k].collides && !spheres.obb_collides[k]) {
        EXPECT_FALSE(exact) << "OBB " << k << ": a miss outside the SACT's epsilon band";
        ++sact_band_misses;
      }
    }
    const SphereRobotReport report = CompareSphereRobot(tree, obbs, CollisionOptions<double>{}, n);
    EXPECT_EQ(report.missed_collisions, sact_band_misses);
    EXPECT_EQ(report.sphere_nodes, spheres.spheres.visits.size());
    std::printf(
        "[ sphere robot, random scene ] %d sphere(s) per OBB: %zu false collisions of %zu OBBs vs the SACT "
        "(%.1f%%), %zu exact collisions, %zu false vs the exact reference; %llu sphere node visits vs %llu "
        "for OBBs\n",
        n, report.false_collisions, report.queries, 100 * report.false_collision_rate(), exact_collisions,
        false_collisions, (unsigned long long)report.sphere_nodes, (unsigned long long)report.obb_nodes);
    EXPECT_GT(report.false_collisions, 0u) << "spheres are larger than the OBB: some false collisions";
    EXPECT_LT(report.false_collision_rate(), 0.5);
  }
  // More spheres hug the OBB tighter: never more false collisions.
  const auto one = CompareSphereRobot(tree, obbs, CollisionOptions<double>{}, 1);
  const auto four = CompareSphereRobot(tree, obbs, CollisionOptions<double>{}, 4);
  EXPECT_LT(four.false_collisions, one.false_collisions);

  // From batches already run (how `rcbench collide` compares without running
  // either kernel again): the same report; the exact outcomes must be one
  // per OBB.
  const SphereRobotBatch four_spheres = CollideSphereBatch(tree, obbs, 4, TraversalOrder::kDepthFirst);
  const SphereRobotReport from_batches = CompareSphereRobot(four_spheres, sact.outcomes);
  EXPECT_EQ(from_batches.spheres_per_obb, 4);
  EXPECT_EQ(from_batches.queries, four.queries);
  EXPECT_EQ(from_batches.obb_collisions, four.obb_collisions);
  EXPECT_EQ(from_batches.sphere_collisions, four.sphere_collisions);
  EXPECT_EQ(from_batches.false_collisions, four.false_collisions);
  EXPECT_EQ(from_batches.missed_collisions, four.missed_collisions);
  EXPECT_EQ(from_batches.obb_nodes, four.obb_nodes);
  EXPECT_EQ(from_batches.sphere_nodes, four.sphere_nodes);
  std::vector<TraversalOutcome> short_by_one(sact.outcomes.begin(), sact.outcomes.end() - 1);
  EXPECT_THROW(CompareSphereRobot(four_spheres, short_by_one), std::invalid_argument);
}

TEST(SphereProgram, RecordsPriceOnEveryBackendBesideTheSact) {
  const std::vector<Aabbd> scene = test::RandomScene(80, 31);
  const FlatBoxTree<float> tree(BuildMedianSplitTree(scene));
  std::vector<Obbf> obbs;
  for (int q = 0; q < 256; ++q) obbs.push_back(test::SceneQuery(scene, 32, q).Cast<float>());
  const SphereRobotBatch spheres = CollideSphereBatch(tree, obbs, 2, TraversalOrder::kDepthFirst);
  const CollisionBatch obb_batch = CollideBatch(tree, obbs, CollisionOptions<float>{});
  const KernelRecord sphere_record = SphereKernelRecord(spheres.spheres);
  const KernelRecord sact_record = SactKernelRecord(obb_batch);
  EXPECT_THROW(SactKernelRecord(spheres.spheres), std::invalid_argument);
  EXPECT_THROW(SphereKernelRecord(obb_batch), std::invalid_argument);
  EXPECT_EQ(sphere_record.step_kind, StepProgramKind::kSphereTest);
  EXPECT_EQ(sphere_record.query_count(), 2 * obbs.size());
  std::size_t misses = 0;
  for (const NodeVisit& v : spheres.spheres.visits) misses += !v.overlaps();
  std::size_t exits = 0;
  for (std::uint8_t e : sphere_record.node_exits) exits += e == 0;
  EXPECT_EQ(exits, misses) << "RETURN_IF #0 exactly where the sphere missed";
  for (const std::string& name : Backend::ModelledNames()) {
    const auto backend = Backend::Create(name, BackendParameters{});
    const BatchCost sphere = backend->Price(sphere_record), sact = backend->Price(sact_record);
    EXPECT_EQ(sphere.nodes, spheres.spheres.visits.size()) << name;
    EXPECT_GT(sphere.cycles, sphere.launch_cycles) << name;
    EXPECT_GT(sphere.energy_joules, 0.0) << name;
    const std::uint64_t sact_ops =
        sact.micro_ops[static_cast<int>(Opcode::kBox)] + sact.micro_ops[static_cast<int>(Opcode::kDot)];
    EXPECT_GT(sact_ops, 0u) << name;
    EXPECT_EQ(sphere.micro_ops[static_cast<int>(Opcode::kBox)] + sphere.micro_ops[static_cast<int>(Opcode::kEdge)] +
                  sphere.micro_ops[static_cast<int>(Opcode::kPre)],
              0u)
        << name << ": the sphere program uses no SACT unit";
    std::printf("[ %s ] SACT %llu cycles (%zu OBBs), spheres %llu cycles (%zu spheres)\n", name.c_str(),
                (unsigned long long)sact.cycles, obbs.size(), (unsigned long long)sphere.cycles,
                sphere_record.query_count());
  }
}

TEST(SphereProgram, MpnetObbsAgainstTheShelf) {
  const char* kObbFile = "collision/mpnet_master_obb.csv";
  RC_REQUIRE_SHARED_DATA(kObbFile);
  std::vector<Obbd> obbs;
  for (const RobotObb& r : ReadObbCsv(test::SharedDataPath(kObbFile))) obbs.push_back(r.obb);
  const std::vector<Aabbd> scene = MakeShelfScene();
  const FlatBoxTree<double> tree(BuildMedianSplitTree(scene));
  for (int n : {1, 2, 4}) {
    const SphereRobotReport report = CompareSphereRobot(tree, obbs, CollisionOptions<double>{}, n);
    std::printf(
        "[ sphere robot, mpnet x shelf ] %d sphere(s) per OBB: %zu false collisions of %zu OBBs (%.1f%%; "
        "%.1f%% of the collision-free), %zu missed\n",
        n, report.false_collisions, report.queries, 100 * report.false_collision_rate(),
        100 * report.false_rate_among_free(), report.missed_collisions);
    EXPECT_EQ(report.missed_collisions, 0u);
    EXPECT_EQ(report.queries, obbs.size());
  }
}

}  // namespace
}  // namespace rc
