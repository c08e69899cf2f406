#include "workloads/delibot/hypothesis_clusters.h"

#include <cmath>
#include <cstdint>
#include <numeric>
#include <stdexcept>
#include <unordered_map>

namespace rc {
namespace {

struct BinKey {
  std::int64_t x, y, heading;
  bool operator==(const BinKey& o) const { return x == o.x && y == o.y && heading == o.heading; }
};

struct BinKeyHash {
  std::size_t operator()(const BinKey& k) const {
    std::uint64_t h = static_cast<std::uint64_t>(k.x) * 0x9E3779B97F4A7C15ull;
    h ^= static_cast<std::uint64_t>(k.y) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
    h ^= static_cast<std::uint64_t>(k.heading) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
    return static_cast<std::size_t>(h);
  }
};

// Union-find over bin indices, with path halving.
struct DisjointSets {
  std::vector<int> parent;
  explicit DisjointSets(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int Find(int a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  }
  void Join(int a, int b) {
    a = Find(a);
    b = Find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

}  // namespace

HypothesisClusters ClusterHypotheses(const std::vector<Pose2>& particles, double xy_bin_m, int heading_bins) {
  if (!(xy_bin_m > 0.0) || heading_bins < 1)
    throw std::invalid_argument("hypothesis clusters need a bin size > 0 m and at least one heading bin");
  const double heading_bin = 2.0 * kPi / heading_bins;
  std::unordered_map<BinKey, int, BinKeyHash> bin_index;
  std::vector<BinKey> bins;
  std::vector<int> bin_of(particles.size());
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const Pose2& p = particles[i];
    std::int64_t h = static_cast<std::int64_t>(std::floor((WrapAngle(p.theta) + kPi) / heading_bin));
    h = ((h % heading_bins) + heading_bins) % heading_bins;  // theta == pi wraps to bin 0
    const BinKey key{static_cast<std::int64_t>(std::floor(p.x / xy_bin_m)),
                     static_cast<std::int64_t>(std::floor(p.y / xy_bin_m)), h};
    const auto [it, inserted] = bin_index.emplace(key, static_cast<int>(bins.size()));
    if (inserted) bins.push_back(key);
    bin_of[i] = it->second;
  }
  DisjointSets sets(bins.size());
  for (std::size_t b = 0; b < bins.size(); ++b)
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dh = -1; dh <= 1; ++dh) {
          const std::int64_t h = ((bins[b].heading + dh) % heading_bins + heading_bins) % heading_bins;
          const auto it = bin_index.find({bins[b].x + dx, bins[b].y + dy, h});
          if (it != bin_index.end()) sets.Join(static_cast<int>(b), it->second);
        }
  // Number the clusters in order of their first particle.
  HypothesisClusters out;
  out.cluster_of.resize(particles.size());
  std::vector<int> cluster_of_root(bins.size(), -1);
  for (std::size_t i = 0; i < particles.size(); ++i) {
    int& cluster = cluster_of_root[static_cast<std::size_t>(sets.Find(bin_of[i]))];
    if (cluster < 0) cluster = out.count++;
    out.cluster_of[i] = cluster;
  }
  return out;
}

}  // namespace rc
