#pragma once
// The `keep` best of a set of scores: the one ranking rule of the claim
// audit's candidates (claim_audit.h) and of SensorModel::BestSelection.
#include <algorithm>
#include <cstddef>
#include <numeric>
#include <vector>

namespace rc {

// Indices of the `keep` highest scores, best first; ties go to the lower
// index, so the choice is the same on every run. Scores are finite.
inline std::vector<std::size_t> BestIndices(const std::vector<double>& scores, std::size_t keep) {
  std::vector<std::size_t> order(scores.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  auto better = [&](std::size_t a, std::size_t b) {
    return scores[a] > scores[b] || (scores[a] == scores[b] && a < b);
  };
  keep = std::min(keep, order.size());
  std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(keep), order.end(), better);
  order.resize(keep);
  return order;
}

}  // namespace rc
