#include "robocore/collision/octree_from_octomap.h"

#include <algorithm>
#include <filesystem>
#include <fstream>

#include <octomap/OcTree.h>

#include "common/input_error.h"
#include "robocore/collision/octomap_file_check.h"

namespace rc {
namespace {

struct OccupiedLeaf {
  octomap::OcTreeKey key;
  unsigned depth;        // OctoMap depth: 0 = root, tree depth = finest
  std::uint64_t morton;  // key bits interleaved, most significant level first
  std::uint32_t box;
};

std::uint64_t Morton(const octomap::OcTreeKey& key) {
  std::uint64_t m = 0;
  for (int bit = 15; bit >= 0; --bit)
    for (int axis = 2; axis >= 0; --axis) m = (m << 1) | ((key[axis] >> bit) & 1u);
  return m;
}

struct OctreeBuilder {
  const std::vector<OccupiedLeaf>& leaves;  // sorted by Morton key
  unsigned tree_depth;
  std::vector<BuildNode> pool;

  // Child of the level-`level` node that a key falls in (0..7).
  unsigned ChildIndex(const octomap::OcTreeKey& key, unsigned level) const {
    const unsigned bit = tree_depth - 1 - level;
    return ((key[0] >> bit) & 1u) | (((key[1] >> bit) & 1u) << 1) | (((key[2] >> bit) & 1u) << 2);
  }

  // The node at depth `level` holding leaves [lo, hi), all in one cell of
  // that level. Leaves never overlap, so a leaf at depth `level` is alone.
  std::uint32_t Build(std::size_t lo, std::size_t hi, unsigned level) {
    BuildNode node;
    if (hi - lo == 1 && leaves[lo].depth == level) {
      node.box = leaves[lo].box;
    } else {
      std::size_t begin = lo;
      while (begin < hi) {  // Morton order keeps each child's leaves contiguous
        const unsigned child = ChildIndex(leaves[begin].key, level);
        std::size_t end = begin + 1;
        while (end < hi && ChildIndex(leaves[end].key, level) == child) ++end;
        node.children.push_back(Build(begin, end, level + 1));
        begin = end;
      }
    }
    pool.push_back(std::move(node));
    return static_cast<std::uint32_t>(pool.size() - 1);
  }
};

std::vector<OccupiedLeaf> CollectLeaves(const octomap::OcTree& tree, std::vector<Aabbd>& boxes) {
  std::vector<OccupiedLeaf> leaves;
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    if (!tree.isNodeOccupied(*it)) continue;
    const octomap::OcTreeKey key = it.getKey();
    const unsigned depth = it.getDepth();
    Aabbd box;
    for (int j = 0; j < 3; ++j) box.centre[j] = tree.keyToCoord(key[j], depth);
    box.half = Eigen::Vector3d::Constant(0.5 * tree.getNodeSize(depth));
    leaves.push_back({key, depth, Morton(key), static_cast<std::uint32_t>(boxes.size())});
    boxes.push_back(box);
  }
  return leaves;
}

}  // namespace

std::vector<Aabbd> OccupiedLeafBoxes(const octomap::OcTree& tree) {
  std::vector<Aabbd> boxes;
  CollectLeaves(tree, boxes);
  return boxes;
}

BoxTree BuildOctreeFromOctoMap(const octomap::OcTree& tree) {
  std::vector<Aabbd> boxes;
  std::vector<OccupiedLeaf> leaves = CollectLeaves(tree, boxes);
  if (leaves.empty()) return LayOutBreadthFirst(BoxTreeKind::kOctree, 8, {}, {}, 0);
  std::sort(leaves.begin(), leaves.end(),
            [](const OccupiedLeaf& a, const OccupiedLeaf& b) { return a.morton < b.morton; });
  OctreeBuilder b{leaves, tree.getTreeDepth(), {}};
  const std::uint32_t root = b.Build(0, leaves.size(), 0);
  return LayOutBreadthFirst(BoxTreeKind::kOctree, 8, std::move(boxes), b.pool, root);
}

BoxTree LoadOctoMapFile(const std::string& path) {
  if (!std::filesystem::exists(path)) throw InputError(path, 0, "", "file not found");
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext != ".bt" && ext != ".ot")
    throw InputError(path, 0, "", "unknown OctoMap extension '" + ext + "' (expected .bt or .ot)");
  // The checked node stream bounds OctoMap's nodes by the file's size (at
  // most eight children of about 100 bytes per two bytes of stream). OctoMap
  // reads exactly that stream, from the checked offset, into a tree of the
  // checked resolution (octomap_file_check.h says why).
  const bool binary = ext == ".bt";
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "", "cannot open OctoMap file");
  const CheckedOctoMapFile checked = CheckOctoMapFile(in, path, binary);
  in.clear();  // the check may stop at the end of the file
  in.seekg(checked.node_stream_at);
  if (!in) throw InputError(path, 0, "", "cannot seek back to the OctoMap file's node stream");
  octomap::OcTree tree(checked.resolution_m);
  if (binary)
    tree.readBinaryData(in);
  else
    tree.readData(in);
  if (!in) throw InputError(path, 0, "data", "OctoMap could not read the node stream");
  return BuildOctreeFromOctoMap(tree);
}

}  // namespace rc
