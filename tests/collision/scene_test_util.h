#pragma once
// Scenes, queries and structural checks shared by the tree tests.
#include <algorithm>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "common/random_stream.h"
#include "pair_generator.h"
#include "robocore/collision/box_tree.h"
#include "robocore/collision/flat_box_tree.h"

namespace rc::test {

// n boxes in [0, 10]^3 m, half extents 0.02-0.8 m; 10% have a zero half
// extent, 30% are stacked exactly on top of an earlier box (touching).
inline std::vector<Aabbd> RandomScene(int n, std::uint64_t seed) {
  RandomStream r(seed, StreamPurpose::kTest, 2, 0);
  std::vector<Aabbd> boxes;
  for (int i = 0; i < n; ++i) {
    Aabbd b;
    b.half = Eigen::Vector3d(r.Uniform(0.02, 0.8), r.Uniform(0.02, 0.8), r.Uniform(0.02, 0.8));
    if (r.Uniform() < 0.1) b.half[r.Below(3)] = 0;
    b.centre = Eigen::Vector3d(r.Uniform(0, 10), r.Uniform(0, 10), r.Uniform(0, 10));
    if (!boxes.empty() && r.Uniform() < 0.3) {
      const Aabbd& below = boxes[r.Below(boxes.size())];
      b.centre = below.centre;
      b.centre.z() = below.centre.z() + below.half.z() + b.half.z();
    }
    boxes.push_back(b);
  }
  return boxes;
}

// Even q: a random OBB anywhere in the scene's bounds (grown by 10% a
// side); odd q: one placed at or near contact with a random scene box
// (pair_generator.h families). OBB sizes are 0.5%-15% of the scene's extent.
inline Obbd SceneQuery(const std::vector<Aabbd>& scene, std::uint64_t seed, std::uint64_t q) {
  Eigen::Vector3d lo = scene.front().centre - scene.front().half, hi = scene.front().centre + scene.front().half;
  for (const Aabbd& b : scene) lo = lo.cwiseMin(b.centre - b.half), hi = hi.cwiseMax(b.centre + b.half);
  const double extent = (hi - lo).maxCoeff();
  RandomStream r(seed, StreamPurpose::kTest, 3, q);
  if (q % 2 == 1) return ObbNearBox(scene[r.Below(scene.size())], extent * r.Uniform(0.005, 0.06), seed, q);
  Obbd o;
  const Eigen::Quaterniond rot(r.Gaussian(), r.Gaussian(), r.Gaussian(), r.Gaussian());
  o.axes = rot.normalized().toRotationMatrix();
  o.half = extent * Eigen::Vector3d(r.Uniform(0.005, 0.15), r.Uniform(0.005, 0.1), r.Uniform(0.0, 0.05));
  for (int j = 0; j < 3; ++j) {
    const double margin = 0.1 * (hi[j] - lo[j]);
    o.centre[j] = r.Uniform(lo[j] - margin, hi[j] + margin);
  }
  return o;
}

// Every box in exactly one leaf; children contiguous, after their parent,
// one level deeper; bounds contain the children's (and a leaf's, its box).
inline void ExpectWellFormed(const BoxTree& tree) {
  std::vector<int> seen(tree.boxes.size(), 0);
  for (std::size_t i = 0; i < tree.nodes.size(); ++i) {
    const BoxTreeNode& n = tree.nodes[i];
    if (n.is_leaf()) {
      ASSERT_LT(n.box, tree.boxes.size());
      ++seen[n.box];
      const Aabbd& b = tree.boxes[n.box];
      for (int j = 0; j < 3; ++j) {
        EXPECT_LE(n.lower[j], static_cast<long double>(b.centre[j]) - b.half[j]);
        EXPECT_GE(n.upper[j], static_cast<long double>(b.centre[j]) + b.half[j]);
      }
      continue;
    }
    EXPECT_GE(n.child_count, 2u) << "single-child nodes are dropped";
    EXPECT_LE(n.child_count, tree.max_children);
    EXPECT_GT(n.first_child, i);
    for (std::uint32_t c = n.first_child; c < n.first_child + n.child_count; ++c) {
      ASSERT_LT(c, tree.nodes.size());
      EXPECT_EQ(tree.nodes[c].depth, n.depth + 1);
      EXPECT_TRUE((n.lower.array() <= tree.nodes[c].lower.array()).all());
      EXPECT_TRUE((n.upper.array() >= tree.nodes[c].upper.array()).all());
    }
  }
  EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int k) { return k == 1; }));
}

// Every internal node's box contains every leaf box below it with at least
// the tree's internal margin to spare (exactly, in long double).
template <typename Scalar>
void ExpectInternalBoxesContainTheirLeaves(const FlatBoxTree<Scalar>& flat) {
  const auto& nodes = flat.nodes();
  const long double margin = 0.999L * flat.internal_margin();
  EXPECT_GT(margin, 0);
  for (const FlatNode<Scalar>& n : nodes) {
    if (n.is_leaf()) continue;
    std::vector<std::uint32_t> stack;
    for (std::uint32_t c = n.first_child; c < n.first_child + n.child_count; ++c) stack.push_back(c);
    while (!stack.empty()) {
      const FlatNode<Scalar>& d = nodes[stack.back()];
      stack.pop_back();
      if (!d.is_leaf()) {
        for (std::uint32_t c = d.first_child; c < d.first_child + d.child_count; ++c) stack.push_back(c);
        continue;
      }
      for (int j = 0; j < 3; ++j) {
        EXPECT_LE(static_cast<long double>(n.centre[j]) - n.half[j] + margin,
                  static_cast<long double>(d.centre[j]) - d.half[j]);
        EXPECT_GE(static_cast<long double>(n.centre[j]) + n.half[j] - margin,
                  static_cast<long double>(d.centre[j]) + d.half[j]);
      }
    }
  }
}

}  // namespace rc::test
