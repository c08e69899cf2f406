#include "robocore/collision/flat_box_tree.h"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace rc {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr int kMarginUlps = 256;

// The Scalar box [c - h, c + h] that contains [lower, upper] (double):
// centre rounded to nearest, half grown until the box covers both ends.
// The ends are evaluated in double and rounded one ulp inward, so the
// check errs on the side of a wider box.
template <typename Scalar>
void ConservativeBox(const Eigen::Vector3d& lower, const Eigen::Vector3d& upper, Scalar* centre, Scalar* half) {
  for (int j = 0; j < 3; ++j) {
    const Scalar c = static_cast<Scalar>(0.5 * lower[j] + 0.5 * upper[j]);
    Scalar h = static_cast<Scalar>(0.5 * upper[j] - 0.5 * lower[j]);
    auto low = [&] { return std::nextafter(double{c} - double{h}, kInf); };
    auto high = [&] { return std::nextafter(double{c} + double{h}, -kInf); };
    while (!(low() <= lower[j] && high() >= upper[j]))  // terminates: h grows every pass
      h = std::nextafter(h, std::numeric_limits<Scalar>::infinity());
    centre[j] = c;
    half[j] = h;
  }
}

}  // namespace

template <typename Scalar>
FlatBoxTree<Scalar>::FlatBoxTree(const BoxTree& tree) : kind_(tree.kind), max_children_(tree.max_children) {
  boxes_.reserve(tree.boxes.size());
  for (const Aabbd& b : tree.boxes) boxes_.push_back(b.template Cast<Scalar>());
  const std::size_t n = tree.nodes.size();
  nodes_.resize(n);
  if (n == 0) return;
  // Bounds of the Scalar-rounded boxes, bottom-up (children follow parents).
  std::vector<Eigen::Vector3d> lower(n), upper(n);
  for (std::size_t i = n; i-- > 0;) {
    const BoxTreeNode& t = tree.nodes[i];
    if (t.child_count > 0xFFFF || t.depth > 0xFFFF)
      throw std::invalid_argument("flat box tree: node " + std::to_string(i) + " exceeds the 16-bit fields");
    FlatNode<Scalar>& f = nodes_[i];
    f.child_count = static_cast<std::uint16_t>(t.child_count);
    f.depth = static_cast<std::uint16_t>(t.depth);
    if (t.is_leaf()) {
      const Aabb<Scalar>& b = boxes_.at(t.box);
      f.first_child = t.box;
      for (int j = 0; j < 3; ++j) {
        f.centre[j] = b.centre[j];
        f.half[j] = b.half[j];
        lower[i][j] = std::nextafter(double{b.centre[j]} - double{b.half[j]}, -kInf);
        upper[i][j] = std::nextafter(double{b.centre[j]} + double{b.half[j]}, kInf);
      }
      continue;
    }
    f.first_child = t.first_child;
    lower[i] = Eigen::Vector3d::Constant(kInf);
    upper[i] = -lower[i];
    for (std::uint32_t c = t.first_child; c < t.first_child + t.child_count; ++c) {
      lower[i] = lower[i].cwiseMin(lower[c]);
      upper[i] = upper[i].cwiseMax(upper[c]);
    }
  }
  // The SACT's rounding near contact is relative to the centre offset and
  // the radii it handles, not to how far from the origin the scene is (the
  // offset of two nearby centres is exact), so the margin follows the
  // scene's size.
  const double scene_half = 0.5 * (upper[0] - lower[0]).maxCoeff();
  const double margin = kMarginUlps * std::numeric_limits<Scalar>::epsilon() * scene_half;
  internal_margin_ = static_cast<Scalar>(margin);
  for (std::size_t i = 0; i < n; ++i) {
    if (nodes_[i].is_leaf()) continue;
    const Eigen::Vector3d lo = lower[i].array() - margin, hi = upper[i].array() + margin;
    ConservativeBox<Scalar>(lo, hi, nodes_[i].centre, nodes_[i].half);
  }
}

template class FlatBoxTree<float>;
template class FlatBoxTree<double>;

}  // namespace rc
