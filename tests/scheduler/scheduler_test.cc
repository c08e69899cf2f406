// Switching decisions of the backend scheduler on scripted counter
// sequences: the exact iterations at which the adaptive policy switches,
// hysteresis against flapping, and the hindsight oracle against brute force.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "backends/scheduler/backend_scheduler.h"

namespace rc {
namespace {

SchedulerOptions Adaptive(double threshold, double hysteresis) {
  SchedulerOptions o;
  o.kind = SchedulerKind::kAdaptive;
  o.threshold_nodes_per_query = threshold;
  o.hysteresis_nodes_per_query = hysteresis;
  return o;
}

// Runs the online policy over a counter sequence: iteration i is scheduled
// from iteration i-1's counter. Returns the iterations at which it switched.
std::vector<int> SwitchIterations(OnlineScheduler& s, const std::vector<double>& nodes_per_query,
                                  std::vector<std::string>* choices = nullptr) {
  std::vector<int> switches;
  std::string previous = s.current();
  for (std::size_t i = 0; i < nodes_per_query.size(); ++i) {
    const std::string& chosen = s.Choose(i == 0 ? -1.0 : nodes_per_query[i - 1]);
    if (choices) choices->push_back(chosen);
    if (chosen != previous) switches.push_back(static_cast<int>(i));
    previous = chosen;
  }
  return switches;
}

TEST(SchedulerTest, LongShortLongPhasesSwitchAtTheExactIterations) {
  // Iterations 0-9 long rays (40 nodes), 10-19 short (5), 20-29 long again.
  std::vector<double> npr;
  for (int i = 0; i < 30; ++i) npr.push_back(i < 10 || i >= 20 ? 40.0 : 5.0);
  OnlineScheduler s(Adaptive(12.0, 0.0));
  std::vector<std::string> choices;
  EXPECT_EQ(SwitchIterations(s, npr, &choices), (std::vector<int>{11, 21}));
  EXPECT_EQ(choices[0], "robocore");
  EXPECT_EQ(choices[10], "robocore") << "iteration 10 only sees iteration 9's long rays";
  EXPECT_EQ(choices[11], "simt");
  EXPECT_EQ(choices[20], "simt");
  EXPECT_EQ(choices[21], "robocore");
}

TEST(SchedulerTest, HysteresisSuppressesFlappingOnANoisyCounter) {
  std::vector<double> npr;
  for (int i = 0; i < 40; ++i) npr.push_back(12.0 + (i % 2 == 0 ? 1.5 : -1.5));  // 13.5, 10.5, ...
  OnlineScheduler without(Adaptive(12.0, 0.0));
  EXPECT_GE(SwitchIterations(without, npr).size(), 30u) << "no hysteresis: switches nearly every iteration";
  OnlineScheduler with(Adaptive(12.0, 2.0));
  EXPECT_EQ(SwitchIterations(with, npr).size(), 0u) << "a 2-node margin absorbs +-1.5 of noise";
  // A real change still gets through the margin.
  npr.insert(npr.end(), 5, 4.0);
  OnlineScheduler with_change(Adaptive(12.0, 2.0));
  EXPECT_EQ(SwitchIterations(with_change, npr), (std::vector<int>{41}));
}

TEST(SchedulerTest, StaticNeverSwitchesAndIgnoresTheCounter) {
  SchedulerOptions o = ParseSchedulerPolicy("static:simt", {"cpu", "simt", "robocore"});
  OnlineScheduler s(o);
  EXPECT_TRUE(SwitchIterations(s, {100, 1, 100, 1}).empty());
  EXPECT_EQ(s.current(), "simt");
}

TEST(SchedulerTest, ParsesPolicies) {
  const std::vector<std::string> names = {"cpu", "simt", "robocore"};
  EXPECT_EQ(ParseSchedulerPolicy("adaptive", names).kind, SchedulerKind::kAdaptive);
  EXPECT_EQ(ParseSchedulerPolicy("oracle", names).kind, SchedulerKind::kOracle);
  EXPECT_EQ(ParseSchedulerPolicy("robocore", names).static_backend, "robocore");
  EXPECT_THROW(ParseSchedulerPolicy("static:gpu", names), std::invalid_argument);
  EXPECT_THROW(ParseSchedulerPolicy("fastest", names), std::invalid_argument);
}

double BruteForceBest(const std::vector<std::vector<double>>& cycles, double switch_cost) {
  const std::size_t n = cycles.size(), k = cycles[0].size();
  double best = INFINITY;
  std::vector<std::size_t> choice(n, 0);
  while (true) {
    best = std::min(best, ScheduleCost(cycles, choice, switch_cost));
    std::size_t i = 0;
    while (i < n && ++choice[i] == k) choice[i++] = 0;
    if (i == n) break;
  }
  return best;
}

TEST(SchedulerTest, OracleEqualsBruteForceIncludingSwitchCosts) {
  std::uint64_t state = 12345;
  auto next = [&] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 40) / (1 << 24);
  };
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<std::vector<double>> cycles(8, std::vector<double>(3));
    for (auto& row : cycles)
      for (double& c : row) c = 100.0 + 100.0 * next();
    for (double switch_cost : {0.0, 15.0, 80.0, 1000.0}) {
      const auto choice = OracleSchedule(cycles, switch_cost);
      EXPECT_NEAR(ScheduleCost(cycles, choice, switch_cost), BruteForceBest(cycles, switch_cost), 1e-9);
    }
  }
}

TEST(SchedulerTest, OracleWithHugeSwitchCostNeverSwitches) {
  std::vector<std::vector<double>> cycles = {{10, 1}, {1, 10}, {10, 1}, {1, 10}};
  const auto free_switch = OracleSchedule(cycles, 0.0);
  EXPECT_EQ(free_switch, (std::vector<std::size_t>{1, 0, 1, 0}));
  const auto costly = OracleSchedule(cycles, 1e9);
  EXPECT_EQ(costly[0], costly[1]);
  EXPECT_EQ(costly[1], costly[2]);
  EXPECT_EQ(costly[2], costly[3]);
}

}  // namespace
}  // namespace rc
