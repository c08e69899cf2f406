// Hypothesis clusters and hypothesis-preserving resampling: the clusters
// split look-alike places and opposite headings and join one cloud (also
// across the +-pi seam); the resampler keeps a trailing hypothesis alive
// without changing the belief the weighted set represents, and reduces to
// plain systematic resampling when there is one hypothesis.
#include <cmath>
#include <limits>
#include <numeric>

#include <gtest/gtest.h>

#include "common/log_domain.h"
#include "workloads/delibot/hypothesis_clusters.h"
#include "workloads/delibot/mcl_options.h"
#include "workloads/delibot/resampling.h"

namespace rc {
namespace {

constexpr double kBin = 1.0;
constexpr int kHeadingBins = 12;

// n particles on a line from (x, y), 0.05 m apart, all facing theta.
std::vector<Pose2> Cloud(double x, double y, double theta, int n) {
  std::vector<Pose2> out;
  for (int i = 0; i < n; ++i) out.push_back({x + 0.05 * (i % 10), y + 0.05 * (i / 10 % 10), theta});
  return out;
}

std::vector<Pose2> Join(std::vector<Pose2> a, const std::vector<Pose2>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

TEST(HypothesisClustersTest, LookAlikeDoorsSixMetresApartAreTwoHypotheses) {
  const HypothesisClusters c = ClusterHypotheses(Join(Cloud(40, 41, 0, 50), Cloud(34, 41, 0, 50)), kBin, kHeadingBins);
  EXPECT_EQ(c.count, 2);
  EXPECT_EQ(c.cluster_of.front(), 0);
  EXPECT_EQ(c.cluster_of.back(), 1);
}

TEST(HypothesisClustersTest, TheSamePlaceFacedBothWaysIsTwoHypotheses) {
  EXPECT_EQ(ClusterHypotheses(Join(Cloud(10, 10, 0, 30), Cloud(10, 10, kPi - 0.1, 30)), kBin, kHeadingBins).count, 2);
}

TEST(HypothesisClustersTest, OneCloudIsOneHypothesisEvenAcrossThePiSeam) {
  std::vector<Pose2> cloud = Cloud(5, 5, kPi - 0.05, 40);
  for (int i = 0; i < 40; i += 2) cloud[i].theta = -kPi + 0.05;  // the same heading, wrapped
  EXPECT_EQ(ClusterHypotheses(cloud, kBin, kHeadingBins).count, 1);
  // A chain of particles 0.9 m apart touches bin to bin: one hypothesis.
  std::vector<Pose2> chain;
  for (int i = 0; i < 20; ++i) chain.push_back({0.9 * i, 3.0, 0.0});
  EXPECT_EQ(ClusterHypotheses(chain, kBin, kHeadingBins).count, 1);
}

TEST(HypothesisClustersTest, RejectsADegenerateGrid) {
  EXPECT_THROW(ClusterHypotheses(Cloud(0, 0, 0, 3), 0.0, kHeadingBins), std::invalid_argument);
  EXPECT_THROW(ClusterHypotheses(Cloud(0, 0, 0, 3), kBin, 0), std::invalid_argument);
}

// Log weights giving each cluster the listed total mass, spread unevenly
// over its members (weights 1, 2, 3, ... inside a cluster).
std::vector<double> WeightsWithMasses(const HypothesisClusters& c, const std::vector<double>& masses) {
  std::vector<double> within(c.cluster_of.size()), total(masses.size(), 0.0);
  std::vector<int> rank(masses.size(), 0);
  for (std::size_t i = 0; i < within.size(); ++i) {
    within[i] = 1.0 + rank[c.cluster_of[i]]++;
    total[c.cluster_of[i]] += within[i];
  }
  std::vector<double> lw(within.size());
  for (std::size_t i = 0; i < lw.size(); ++i)
    lw[i] = std::log(masses[c.cluster_of[i]] * within[i] / total[c.cluster_of[i]]);
  NormalizeLogWeights(lw);
  return lw;
}

struct ClusterTally {
  std::vector<int> slots;
  std::vector<double> mass;
};

ClusterTally Tally(const HypothesisClusters& c, const WeightedResample& r) {
  ClusterTally t{std::vector<int>(c.count, 0), std::vector<double>(c.count, 0.0)};
  for (std::size_t s = 0; s < r.ancestors.size(); ++s) {
    const int k = c.cluster_of[r.ancestors[s]];
    ++t.slots[k];
    t.mass[k] += std::exp(r.log_weights[s]);
  }
  return t;
}

auto Offsets(double u) {
  return [u](std::size_t pass) { return std::fmod(u + 0.37 * static_cast<double>(pass), 1.0); };
}

TEST(HypothesisResamplingTest, KeepsATrailingHypothesisAliveWithItsTrueMass) {
  // Plain resampling gives a hypothesis holding 0.1 % of the mass one of
  // 1000 slots; the floor keeps 20 particles there, each weighing 0.005 %.
  const std::vector<Pose2> particles = Join(Cloud(40, 41, 0, 500), Cloud(34, 41, 0, 500));
  const HypothesisClusters c = ClusterHypotheses(particles, kBin, kHeadingBins);
  const std::vector<double> lw = WeightsWithMasses(c, {0.999, 0.001});
  const WeightedResample r = HypothesisPreservingResample(lw, c, 1000, {20, 100.0}, Offsets(0.42));
  ASSERT_EQ(r.ancestors.size(), 1000u);
  ASSERT_EQ(r.log_weights.size(), 1000u);
  EXPECT_EQ(r.floored_clusters, 1);
  const ClusterTally t = Tally(c, r);
  EXPECT_EQ(t.slots[1], 20);
  EXPECT_EQ(t.slots[0], 980);
  EXPECT_NEAR(t.mass[0], 0.999, 1e-12);
  EXPECT_NEAR(t.mass[1], 0.001, 1e-12);
  // Inside each hypothesis the draw follows the weights: the weighted mean x
  // of the resampled set matches the input's within a slot's share.
  double mean_in = 0.0, mean_out = 0.0;
  for (std::size_t i = 0; i < particles.size(); ++i) mean_in += std::exp(lw[i]) * particles[i].x;
  for (std::size_t s = 0; s < r.ancestors.size(); ++s)
    mean_out += std::exp(r.log_weights[s]) * particles[r.ancestors[s]].x;
  EXPECT_NEAR(mean_out, mean_in, 0.01);
}

TEST(HypothesisResamplingTest, AHypothesisBeyondTheWindowIsResampledPlainly) {
  const std::vector<Pose2> particles = Join(Cloud(40, 41, 0, 500), Cloud(34, 41, 0, 500));
  const HypothesisClusters c = ClusterHypotheses(particles, kBin, kHeadingBins);
  // 1e-9 of the mass is 20.7 nats behind: outside a 10-nat window.
  const std::vector<double> lw = WeightsWithMasses(c, {1.0 - 1e-9, 1e-9});
  const WeightedResample r = HypothesisPreservingResample(lw, c, 1000, {20, 10.0}, Offsets(0.42));
  EXPECT_EQ(r.floored_clusters, 0);
  EXPECT_EQ(Tally(c, r).slots[1], 0);
}

TEST(HypothesisResamplingTest, WithOneHypothesisItIsSystematicResampling) {
  const std::vector<Pose2> particles = Cloud(12, 7, 1.0, 400);
  const HypothesisClusters c = ClusterHypotheses(particles, kBin, kHeadingBins);
  ASSERT_EQ(c.count, 1);
  std::vector<double> lw(particles.size());
  for (std::size_t i = 0; i < lw.size(); ++i) lw[i] = std::log(1.0 + i % 5);
  NormalizeLogWeights(lw);
  const WeightedResample r = HypothesisPreservingResample(lw, c, 300, {20, 100.0}, Offsets(0.42));
  EXPECT_EQ(r.ancestors, SystematicResample(lw, 0.42, 300));
  for (double w : r.log_weights) EXPECT_DOUBLE_EQ(w, -std::log(300.0));
}

// A cloud of 200 particles at the origin, then count - 1 clouds of 10, 3 m
// apart along x: count separate hypotheses.
std::vector<Pose2> HypothesesInARow(std::size_t count) {
  std::vector<Pose2> particles = Cloud(0, 0, 0, 200);
  for (std::size_t k = 1; k < count; ++k) particles = Join(particles, Cloud(3.0 * k, 0, 0, 10));
  return particles;
}

// One hypothesis per mass (HypothesesInARow) resampled into 1000 slots at a
// floor of 20 particles and a 100-nat window.
struct RowResample {
  HypothesisClusters clusters;
  WeightedResample resampled;
  ClusterTally tally;
};

RowResample ResampleARow(const std::vector<double>& masses, double u) {
  RowResample out;
  out.clusters = ClusterHypotheses(HypothesesInARow(masses.size()), kBin, kHeadingBins);
  if (out.clusters.count != static_cast<int>(masses.size())) {
    ADD_FAILURE() << out.clusters.count << " clusters for " << masses.size() << " hypotheses";
    return out;
  }
  out.resampled = HypothesisPreservingResample(WeightsWithMasses(out.clusters, masses), out.clusters, 1000, {20, 100.0},
                                               Offsets(u));
  out.tally = Tally(out.clusters, out.resampled);
  return out;
}

TEST(HypothesisResamplingTest, FlooredHypothesesTakeAtMostHalfTheSlots) {
  // One heavy hypothesis and 60 light ones 3 m apart: 1000 slots at a floor
  // of 20 hold at most 25 light hypotheses; the heaviest light ones win.
  std::vector<double> masses = {0.9};
  for (int k = 0; k < 60; ++k) masses.push_back(0.1 * (60 - k) / 1830.0);  // decreasing, summing to 0.1
  const RowResample row = ResampleARow(masses, 0.1);
  ASSERT_EQ(row.tally.slots.size(), masses.size());
  const HypothesisClusters& c = row.clusters;
  const WeightedResample& r = row.resampled;
  const ClusterTally& t = row.tally;
  EXPECT_EQ(r.floored_clusters, 25);
  for (int k = 1; k <= 25; ++k) EXPECT_EQ(t.slots[k], 20) << "hypothesis " << k;
  EXPECT_EQ(std::accumulate(t.slots.begin(), t.slots.end(), 0), 1000);
  // A floored hypothesis keeps its mass exactly; the others share the rest
  // by systematic resampling, each to within one shared slot's weight.
  const double slot_weight = std::exp(r.log_weights.front());
  double shared_in = 0.0, shared_out = 0.0;
  for (int k = 0; k < c.count; ++k) {
    if (k >= 1 && k <= 25) {
      EXPECT_NEAR(t.mass[k], masses[k], 1e-12) << "hypothesis " << k;
    } else {
      EXPECT_LE(std::abs(t.mass[k] - masses[k]), slot_weight + 1e-12) << "hypothesis " << k;
      shared_in += masses[k];
      shared_out += t.mass[k];
    }
  }
  EXPECT_NEAR(shared_out, shared_in, 1e-12);
}

TEST(HypothesisResamplingTest, TheCapGoesToTheHeaviestHypotheses) {
  // Masses 0.949, 0.021 and 30 x 0.001 over 1000 slots at a floor of 20:
  // the 0.021 hypothesis starts above the floor (21 slots) and falls below
  // it as lighter ones are floored. It must still get its 20 particles
  // before the 25-hypothesis cap is filled by hypotheses 21 times lighter.
  std::vector<double> masses = {0.949, 0.021};
  masses.resize(32, 0.001);
  const RowResample row = ResampleARow(masses, 0.3);
  ASSERT_EQ(row.tally.slots.size(), masses.size());
  EXPECT_EQ(row.resampled.floored_clusters, 25);
  EXPECT_EQ(row.tally.slots[1], 20);
  EXPECT_NEAR(row.tally.mass[1], 0.021, 1e-12);
}

TEST(HypothesisResamplingTest, AHypothesisWithNoWeightIsNeverKept) {
  const std::vector<Pose2> particles = Join(Cloud(40, 41, 0, 500), Cloud(34, 41, 0, 500));
  const HypothesisClusters c = ClusterHypotheses(particles, kBin, kHeadingBins);
  std::vector<double> lw(particles.size(), -std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < 500; ++i) lw[i] = -std::log(500.0);  // the second cloud: all in walls
  const WeightedResample r = HypothesisPreservingResample(lw, c, 1000, {20, 1e4}, Offsets(0.42));
  EXPECT_EQ(r.floored_clusters, 0);
  EXPECT_EQ(Tally(c, r).slots[1], 0);
  EXPECT_EQ(HypothesesAlive(ClusterLogMasses(lw, c), 1e4), 1);
}

TEST(HypothesisResamplingTest, RejectsClustersThatDoNotCoverTheWeights) {
  const HypothesisClusters c = ClusterHypotheses(Cloud(0, 0, 0, 10), kBin, kHeadingBins);
  const std::vector<double> lw(11, -std::log(11.0));
  EXPECT_THROW(HypothesisPreservingResample(lw, c, 11, {2, 10.0}, Offsets(0.5)), std::invalid_argument);
  EXPECT_THROW(ClusterLogMasses(lw, c), std::invalid_argument);
}

TEST(HypothesisResamplingTest, OptionsBoundTheFloor) {
  MclOptions o;
  std::string error;
  o.hypothesis_floor.min_particles = o.particle_count / 2 + 1;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("hypothesis floor"), std::string::npos);
  o.hypothesis_floor = {20, -1.0};
  EXPECT_FALSE(o.IsValid(&error));
  o.hypothesis_floor = {20, 100.0};
  EXPECT_TRUE(o.IsValid(&error)) << error;
}

}  // namespace
}  // namespace rc
