// The planar quadtree (2D occupancy grid) and the OctoMap octree: their
// answers equal testing every occupied cell / every occupied leaf, their
// structure, and the OctoMap file loaders.

#include <filesystem>
#include <fstream>
#include <set>

#include <gtest/gtest.h>
#include <octomap/OcTree.h>

#include "common/input_error.h"
#include "common/random_stream.h"
#include "robocore/collision/octree_from_octomap.h"
#include "robocore/collision/quadtree_from_grid.h"
#include "robocore/collision/tree_collision.h"
#include "scene_test_util.h"
#include "support/input_error_expectations.h"
#include "support/temp_dir.h"

namespace rc {
namespace {

using Vec3 = Eigen::Vector3d;

OccupancyGrid RandomGrid(int nx, int ny, std::uint64_t seed) {
  OccupancyGrid g(nx, ny, 0.1);
  RandomStream r(seed, StreamPurpose::kTest, 4, 0);
  for (int x = 0; x < nx; ++x)
    for (int y = 0; y < ny; ++y) {
      const double u = r.Uniform();
      g.Set(x, y, u < 0.2 ? CellState::kOccupied : u < 0.25 ? CellState::kUnknown : CellState::kFree);
    }
  return g;
}

// OBB queries over a scene, with each answer compared to `brute`.
template <typename Brute>
void ExpectQueriesMatch(const BoxTree& tree, Brute&& brute, std::uint64_t seed, int queries) {
  const FlatBoxTree<double> flat(tree);
  int collisions = 0;
  for (int q = 0; q < queries; ++q) {
    const Obbd obb = test::SceneQuery(tree.boxes, seed, q);
    const bool expected = brute(obb);
    ASSERT_EQ(CollideObb(flat, obb, CollisionOptions<double>{}).collides, expected) << q;
    collisions += expected;
  }
  EXPECT_GT(collisions, queries / 10);
  EXPECT_LT(collisions, queries * 9 / 10);
}

TEST(QuadtreeFromGrid, LeavesAreTheOccupiedCellsAndTheTreeIsPlanar) {
  const OccupancyGrid grid = RandomGrid(37, 53, 1);
  QuadtreeOptions options;
  const BoxTree tree = BuildQuadtreeFromGrid(grid, options);
  EXPECT_EQ(tree.kind, BoxTreeKind::kQuadtree);
  EXPECT_EQ(tree.max_children, 4u);
  EXPECT_EQ(tree.boxes.size(), grid.CountCells(CellState::kOccupied));
  test::ExpectWellFormed(tree);
  EXPECT_LE(tree.nodes.size(), 2 * tree.boxes.size() - 1);  // every internal node branches
  std::set<std::pair<long, long>> cells;
  for (const Aabbd& b : tree.boxes) {
    const long ix = std::lround(b.centre.x() / 0.1 - 0.5), iy = std::lround(b.centre.y() / 0.1 - 0.5);
    EXPECT_EQ(grid.At(ix, iy), CellState::kOccupied);
    const Aabbd expected = GridCellBox(grid, ix, iy, options);
    EXPECT_EQ(b.centre, expected.centre);
    EXPECT_EQ(b.half, expected.half);
    EXPECT_EQ(b.centre.z() - b.half.z(), options.z_min_m);
    cells.insert({ix, iy});
  }
  EXPECT_EQ(cells.size(), tree.boxes.size());
  QuadtreeOptions with_unknown;
  with_unknown.unknown_is_occupied = true;
  EXPECT_EQ(BuildQuadtreeFromGrid(grid, with_unknown).boxes.size(),
            grid.CountCells(CellState::kOccupied) + grid.CountCells(CellState::kUnknown));
  EXPECT_TRUE(BuildQuadtreeFromGrid(OccupancyGrid(8, 8, 0.1)).nodes.empty());
  QuadtreeOptions bad;
  bad.z_max_m = -1;
  EXPECT_THROW(BuildQuadtreeFromGrid(grid, bad), std::invalid_argument);
}

TEST(QuadtreeFromGrid, TreeEqualsTestingEveryOccupiedCell) {
  const OccupancyGrid grid = RandomGrid(64, 45, 2);
  QuadtreeOptions options;
  options.z_max_m = 0.5;
  const BoxTree tree = BuildQuadtreeFromGrid(grid, options);
  auto every_cell = [&](const Obbd& obb) {
    for (int x = 0; x < grid.size_x(); ++x)
      for (int y = 0; y < grid.size_y(); ++y)
        if (grid.At(x, y) == CellState::kOccupied && TestObbAabb(obb, GridCellBox(grid, x, y, options)).overlaps())
          return true;
    return false;
  };
  ExpectQueriesMatch(tree, every_cell, 3, 4000);
}

// An OcTree with scattered occupied voxels, some free ones, and one block of
// eight equal occupied voxels that OctoMap prunes into a coarser leaf.
octomap::OcTree MakeOcTree() {
  octomap::OcTree tree(0.05);
  RandomStream r(5, StreamPurpose::kTest, 5, 0);
  for (int k = 0; k < 1500; ++k) {
    const octomap::point3d p(r.Uniform(0, 2), r.Uniform(-1, 1), r.Uniform(0, 1.5));
    tree.updateNode(p, r.Uniform() < 0.8);
  }
  for (int k = 0; k < 20; ++k)  // saturate so the eight children are equal, then pruned
    for (float dx : {0.025f, 0.075f})
      for (float dy : {0.025f, 0.075f})
        for (float dz : {0.025f, 0.075f}) tree.updateNode(octomap::point3d(3.0f + dx, 3.0f + dy, 3.0f + dz), true);
  tree.prune();
  return tree;
}

TEST(OctreeFromOctoMap, LeavesAreTheOccupiedLeavesAndTheTreeEqualsTestingThemAll) {
  const octomap::OcTree octomap_tree = MakeOcTree();
  std::size_t occupied = 0;
  bool coarse_leaf = false;
  for (auto it = octomap_tree.begin_leafs(); it != octomap_tree.end_leafs(); ++it)
    if (octomap_tree.isNodeOccupied(*it)) ++occupied, coarse_leaf = coarse_leaf || it.getDepth() < 16;
  ASSERT_TRUE(coarse_leaf) << "the test scene should hold a pruned, coarser leaf";
  const BoxTree tree = BuildOctreeFromOctoMap(octomap_tree);
  EXPECT_EQ(tree.kind, BoxTreeKind::kOctree);
  EXPECT_EQ(tree.boxes.size(), occupied);
  EXPECT_LE(tree.max_children, 8u);
  test::ExpectWellFormed(tree);
  const std::vector<Aabbd> leaves = OccupiedLeafBoxes(octomap_tree);
  for (const Aabbd& b : leaves) {  // cubes, of an OctoMap node size
    EXPECT_EQ(b.half.x(), b.half.y());
    EXPECT_EQ(b.half.x(), b.half.z());
  }
  auto every_leaf = [&](const Obbd& obb) { return CollidesBruteForce(leaves, obb, SactOptions<double>{}); };
  ExpectQueriesMatch(tree, every_leaf, 6, 4000);
}

double Volume(const std::vector<Aabbd>& boxes) {
  double v = 0;
  for (const Aabbd& b : boxes) v += 8 * b.half.prod();
  return v;
}

TEST(OctreeFromOctoMap, LoadsBtAndOtFiles) {
  octomap::OcTree original = MakeOcTree();
  const std::vector<Aabbd> leaves = OccupiedLeafBoxes(original);
  const std::string ot = test::ProgramTempPath("scene.ot"), bt = test::ProgramTempPath("scene.bt");
  ASSERT_TRUE(original.write(ot));
  const BoxTree from_ot = LoadOctoMapFile(ot);
  EXPECT_EQ(from_ot.boxes.size(), leaves.size());
  EXPECT_DOUBLE_EQ(Volume(from_ot.boxes), Volume(leaves));
  // .bt keeps only maximum-likelihood occupancy and may prune further:
  // the same occupied volume, perhaps in fewer leaves.
  ASSERT_TRUE(original.writeBinary(bt));
  const BoxTree from_bt = LoadOctoMapFile(bt);
  EXPECT_LE(from_bt.boxes.size(), leaves.size());
  EXPECT_NEAR(Volume(from_bt.boxes), Volume(leaves), 1e-9);
  test::ExpectWellFormed(from_bt);
  std::filesystem::remove(ot);
  std::filesystem::remove(bt);

  EXPECT_THROW(LoadOctoMapFile(test::ProgramTempPath("missing.bt")), InputError);
  const std::string garbage = test::ProgramTempPath("garbage.bt");
  std::ofstream(garbage) << "not an octree\n";
  EXPECT_THROW(LoadOctoMapFile(garbage), InputError);
  std::filesystem::remove(garbage);
  const std::string wrong = test::ProgramTempPath("scene.pcd");
  std::ofstream(wrong) << "x\n";
  EXPECT_THROW(LoadOctoMapFile(wrong), InputError);
  std::filesystem::remove(wrong);
}

// Findings of tests/fuzz: OctoMap reads the node stream by unbounded
// recursion, and a truncated stream leaves its child mask uninitialized.
TEST(OctreeFromOctoMapBadInput, NodeStreamDeeperThanAnOcTreeOrTruncated) {
  const std::string header = "# Octomap OcTree binary file\n# (comment)\nid OcTree\nsize 3\nres 0.1\ndata\n";
  const std::string deep = test::ProgramTempPath("deep.bt");
  std::ofstream(deep, std::ios::binary) << header << std::string(200, '\xff');  // every child an inner node
  const InputError e = test::InputErrorFrom([&] { LoadOctoMapFile(deep); }, deep);
  EXPECT_EQ(e.field(), "data");
  EXPECT_NE(std::string(e.what()).find("deeper than an OcTree's 16 levels"), std::string::npos) << e.what();
  const std::string cut = test::ProgramTempPath("cut.bt");
  std::ofstream(cut, std::ios::binary) << header << std::string(1, '\x03');
  EXPECT_THROW(LoadOctoMapFile(cut), InputError);
  const std::string other = test::ProgramTempPath("color.ot");
  std::ofstream(other, std::ios::binary) << "# Octomap OcTree file\nid ColorOcTree\nres 0.1\ndata\n";
  EXPECT_THROW(LoadOctoMapFile(other), InputError);
}

}  // namespace
}  // namespace rc
