#pragma once
// The SACT query file of the GPU check (docs/gpu_check.md): one collision
// scene's flattened box tree, the robot-link OBBs queried against it and
// the host's outcomes, written by gpu_sact_export and read by
// sact_on_gpu.cu. Plain C++17, for nvcc as well.
//
// Layout, little-endian, no padding, in this order:
//   char[8]   magic "RCSACT1"
//   char[32]  scene name, NUL-padded
//   uint64    nodes (m), queries (n)
//   float64   parallel_epsilon (SactOptions; unitless)
//   FlatBoxTree<double> (robocore/collision/flat_box_tree.h), per node:
//     float64 node_centre[3m], node_half[3m]   m, x y z per node
//     uint32  first_child[m]; uint16 child_count[m], depth[m]
//   Obb<double>, per query:
//     float64 obb_centre[3n], obb_axes[9n], obb_half[3n]
//             (axes column-major as Eigen stores them: box axis i is
//             obb_axes[9q + 3i .. 9q + 3i + 2])
//   the host's TraversalOutcome per query:
//     uint8 collides[n]; uint32 colliding_box[n], nodes_visited[n]
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "benchmarks/gpu/binary_io.h"

namespace rc::gpu_check {

inline constexpr char kSactFileMagic[8] = "RCSACT1";
inline constexpr std::size_t kSceneNameBytes = 32;

struct SactQueryFile {
  std::string scene;  // at most kSceneNameBytes - 1 characters
  double parallel_epsilon = 0;
  std::vector<double> node_centre, node_half;  // 3 per node
  std::vector<std::uint32_t> first_child;
  std::vector<std::uint16_t> child_count, depth;
  std::vector<double> obb_centre, obb_axes, obb_half;  // 3, 9, 3 per query
  std::vector<std::uint8_t> collides;
  std::vector<std::uint32_t> colliding_box, nodes_visited;

  std::size_t nodes() const { return first_child.size(); }
  std::size_t queries() const { return collides.size(); }
};

// Every array must hold its count; returns false with the reason if not,
// or if the file cannot be written.
inline bool WriteSactFile(const SactQueryFile& f, const std::string& path, std::string* error) {
  using namespace binary_io;
  const std::size_t m = f.nodes(), n = f.queries();
  if (f.scene.size() >= kSceneNameBytes) return Fail(error, path, "scene name longer than 31 characters");
  if (f.node_centre.size() != 3 * m || f.node_half.size() != 3 * m || f.child_count.size() != m ||
      f.depth.size() != m || f.obb_centre.size() != 3 * n || f.obb_axes.size() != 9 * n || f.obb_half.size() != 3 * n ||
      f.colliding_box.size() != n || f.nodes_visited.size() != n)
    return Fail(error, path, "array sizes disagree with the node and query counts");
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) return Fail(error, path, "cannot open for writing");
  out.write(kSactFileMagic, sizeof(kSactFileMagic));
  char name[kSceneNameBytes] = {};
  std::memcpy(name, f.scene.data(), f.scene.size());
  out.write(name, sizeof(name));
  Put(out, static_cast<std::uint64_t>(m));
  Put(out, static_cast<std::uint64_t>(n));
  Put(out, f.parallel_epsilon);
  PutArray(out, f.node_centre);
  PutArray(out, f.node_half);
  PutArray(out, f.first_child);
  PutArray(out, f.child_count);
  PutArray(out, f.depth);
  PutArray(out, f.obb_centre);
  PutArray(out, f.obb_axes);
  PutArray(out, f.obb_half);
  PutArray(out, f.collides);
  PutArray(out, f.colliding_box);
  PutArray(out, f.nodes_visited);
  out.close();
  if (!out) return Fail(error, path, "write failed");
  return true;
}

// Reads a file WriteSactFile wrote. Refuses, naming the field, a wrong
// magic, an impossible count, a truncated array, a child index out of the
// tree, or bytes after the last array.
inline bool ReadSactFile(const std::string& path, SactQueryFile* f, std::string* error) {
  using namespace binary_io;
  std::ifstream in(path, std::ios::binary);
  if (!in) return Fail(error, path, "cannot open");
  char magic[8] = {};
  if (!in.read(magic, sizeof(magic)) || std::memcmp(magic, kSactFileMagic, sizeof(magic)) != 0)
    return Fail(error, path, "magic: not an RCSACT1 query file");
  char name[kSceneNameBytes] = {};
  std::uint64_t m = 0, n = 0;
  if (!in.read(name, sizeof(name)) || !Get(in, &m) || !Get(in, &n) || !Get(in, &f->parallel_epsilon))
    return Fail(error, path, "header: truncated");
  name[kSceneNameBytes - 1] = '\0';
  f->scene = name;
  if (m == 0 || m > (std::uint64_t{1} << 26)) return Fail(error, path, "nodes: must be 1 to 2^26");
  if (n == 0 || n > (std::uint64_t{1} << 26)) return Fail(error, path, "queries: must be 1 to 2^26");
  if (!GetArray(in, 3 * m, &f->node_centre)) return Fail(error, path, "node_centre: truncated");
  if (!GetArray(in, 3 * m, &f->node_half)) return Fail(error, path, "node_half: truncated");
  if (!GetArray(in, m, &f->first_child)) return Fail(error, path, "first_child: truncated");
  if (!GetArray(in, m, &f->child_count)) return Fail(error, path, "child_count: truncated");
  if (!GetArray(in, m, &f->depth)) return Fail(error, path, "depth: truncated");
  for (std::size_t i = 0; i < m; ++i)
    if (f->child_count[i] > 0 && std::uint64_t{f->first_child[i]} + f->child_count[i] > m)
      return Fail(error, path, "first_child: a child index is outside the tree");
  if (!GetArray(in, 3 * n, &f->obb_centre)) return Fail(error, path, "obb_centre: truncated");
  if (!GetArray(in, 9 * n, &f->obb_axes)) return Fail(error, path, "obb_axes: truncated");
  if (!GetArray(in, 3 * n, &f->obb_half)) return Fail(error, path, "obb_half: truncated");
  if (!GetArray(in, n, &f->collides)) return Fail(error, path, "collides: truncated");
  if (!GetArray(in, n, &f->colliding_box)) return Fail(error, path, "colliding_box: truncated");
  if (!GetArray(in, n, &f->nodes_visited)) return Fail(error, path, "nodes_visited: truncated");
  if (in.peek() != std::ifstream::traits_type::eof()) return Fail(error, path, "bytes after the last array");
  return true;
}

}  // namespace rc::gpu_check
