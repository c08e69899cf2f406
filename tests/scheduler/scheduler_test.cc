// Switching decisions of the backend scheduler on scripted sequences: the
// exact iterations at which the threshold policy switches on a counter and
// the adaptive policy on predicted costs, hysteresis against flapping, the
// switch cost paid back before a switch, and the hindsight oracle against
// brute force.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "backends/scheduler/backend_scheduler.h"

namespace rc {
namespace {

SchedulerOptions Threshold(double threshold, double hysteresis) {
  SchedulerOptions o;
  o.kind = SchedulerKind::kThreshold;
  o.threshold_nodes_per_query = threshold;
  o.hysteresis_nodes_per_query = hysteresis;
  return o;
}

OnlineScheduler ThresholdPolicy(double threshold, double hysteresis) {
  return OnlineScheduler(Threshold(threshold, hysteresis), {});
}

// Runs the online policy over a sequence of observations: iteration i is
// scheduled from iteration i-1's. Returns the iterations at which it
// switched.
std::vector<int> SwitchIterations(OnlineScheduler& s, const std::vector<IterationObservation>& observed,
                                  std::vector<std::string>* choices = nullptr) {
  std::vector<int> switches;
  std::string previous = s.current();
  for (std::size_t i = 0; i < observed.size(); ++i) {
    const std::string& chosen = s.Choose(i == 0 ? IterationObservation{} : observed[i - 1]);
    if (choices) choices->push_back(chosen);
    if (chosen != previous) switches.push_back(static_cast<int>(i));
    previous = chosen;
  }
  return switches;
}

std::vector<int> SwitchIterations(OnlineScheduler& s, const std::vector<double>& nodes_per_query,
                                  std::vector<std::string>* choices = nullptr) {
  std::vector<IterationObservation> observed;
  for (double n : nodes_per_query) observed.push_back({true, n, {}});
  return SwitchIterations(s, observed, choices);
}

// Observations carrying each candidate's modelled cycles.
std::vector<IterationObservation> Costs(const std::vector<std::vector<double>>& cycles) {
  std::vector<IterationObservation> observed;
  for (const auto& row : cycles) observed.push_back({true, 10.0, row});
  return observed;
}

TEST(SchedulerTest, LongShortLongPhasesSwitchAtTheExactIterations) {
  // Iterations 0-9 long rays (40 nodes), 10-19 short (5), 20-29 long again.
  std::vector<double> npr;
  for (int i = 0; i < 30; ++i) npr.push_back(i < 10 || i >= 20 ? 40.0 : 5.0);
  OnlineScheduler s = ThresholdPolicy(12.0, 0.0);
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
  OnlineScheduler without = ThresholdPolicy(12.0, 0.0);
  EXPECT_GE(SwitchIterations(without, npr).size(), 30u) << "no hysteresis: switches nearly every iteration";
  OnlineScheduler with = ThresholdPolicy(12.0, 2.0);
  EXPECT_EQ(SwitchIterations(with, npr).size(), 0u) << "a 2-node margin absorbs +-1.5 of noise";
  // A real change still gets through the margin.
  npr.insert(npr.end(), 5, 4.0);
  OnlineScheduler with_change = ThresholdPolicy(12.0, 2.0);
  EXPECT_EQ(SwitchIterations(with_change, npr), (std::vector<int>{41}));
}

TEST(SchedulerTest, StaticNeverSwitchesAndIgnoresTheCounter) {
  SchedulerOptions o = ParseSchedulerPolicy("static:simt", {"cpu", "simt", "robocore"});
  OnlineScheduler s(o, {"simt", "robocore"});
  EXPECT_TRUE(SwitchIterations(s, std::vector<double>{100, 1, 100, 1}).empty());
  EXPECT_EQ(s.current(), "simt");
}

TEST(SchedulerTest, ParsesPolicies) {
  const std::vector<std::string> names = {"cpu", "simt", "robocore"};
  EXPECT_EQ(ParseSchedulerPolicy("adaptive", names).kind, SchedulerKind::kAdaptive);
  EXPECT_EQ(ParseSchedulerPolicy("threshold", names).kind, SchedulerKind::kThreshold);
  EXPECT_EQ(ParseSchedulerPolicy("oracle", names).kind, SchedulerKind::kOracle);
  EXPECT_EQ(ParseSchedulerPolicy("robocore", names).static_backend, "robocore");
  EXPECT_THROW(ParseSchedulerPolicy("static:gpu", names), std::invalid_argument);
  EXPECT_THROW(ParseSchedulerPolicy("fastest", names), std::invalid_argument);
}

TEST(SchedulerTest, ParsesCandidates) {
  const std::vector<std::string> names = {"simt", "ttaplus-cr", "robocore"};
  EXPECT_EQ(ParseCandidates("robocore,simt", names), (std::vector<std::string>{"robocore", "simt"}));
  EXPECT_THROW(ParseCandidates("robocore,gpu", names), std::invalid_argument);
  EXPECT_THROW(ParseCandidates("simt,simt", names), std::invalid_argument);
  EXPECT_THROW(ParseCandidates("", names), std::invalid_argument);
}

TEST(SchedulerTest, AdaptiveFollowsThePreviousIterationsCheapestCandidate) {
  // Candidates {simt, robocore}; robocore cheaper in iterations 3-7.
  std::vector<std::vector<double>> cycles;
  for (int i = 0; i < 12; ++i)
    cycles.push_back(i >= 3 && i < 8 ? std::vector<double>{100, 60} : std::vector<double>{60, 100});
  SchedulerOptions o = ParseSchedulerPolicy("adaptive", {"simt", "robocore"});
  o.switch_cost_cycles = 0.0;
  OnlineScheduler s(o, {"simt", "robocore"});
  std::vector<std::string> choices;
  // It starts on the first candidate, and each change is seen one
  // iteration late: iteration 4 is the first scheduled from a cheaper
  // robocore, iteration 9 the first from a cheaper simt.
  EXPECT_EQ(SwitchIterations(s, Costs(cycles), &choices), (std::vector<int>{4, 9}));
  EXPECT_EQ(choices.front(), "simt");
  EXPECT_EQ(choices[4], "robocore");
}

TEST(SchedulerTest, AdaptiveSwitchesOnlyOnceTheSavingsPayForTheSwitch) {
  // robocore saves 10 cycles per iteration from iteration 0 on; a switch
  // costs 35, so the policy waits until 4 iterations of savings (40 >= 35)
  // have been seen: it switches at iteration 4.
  std::vector<std::vector<double>> cycles(10, {110, 100});
  SchedulerOptions o = ParseSchedulerPolicy("adaptive", {"simt", "robocore"});
  o.switch_cost_cycles = 35.0;
  OnlineScheduler s(o, {"simt", "robocore"});
  EXPECT_EQ(SwitchIterations(s, Costs(cycles)), (std::vector<int>{4}));
  // Savings that alternate with losses never add up: no switch.
  std::vector<std::vector<double>> alternating;
  for (int i = 0; i < 20; ++i)
    alternating.push_back(i % 2 ? std::vector<double>{110, 100} : std::vector<double>{100, 130});
  OnlineScheduler t(o, {"simt", "robocore"});
  EXPECT_TRUE(SwitchIterations(t, Costs(alternating)).empty());
}

TEST(SchedulerTest, AdaptivePicksTheRivalWithTheMostRegretAmongSeveral) {
  // Three candidates; both rivals are cheaper than ttaplus, robocore by more.
  std::vector<std::vector<double>> cycles(3, {100, 90, 70});
  SchedulerOptions o = ParseSchedulerPolicy("adaptive", {"ttaplus", "simt", "robocore"});
  o.switch_cost_cycles = 0.0;
  OnlineScheduler s(o, {"ttaplus", "simt", "robocore"});
  std::vector<std::string> choices;
  EXPECT_EQ(SwitchIterations(s, Costs(cycles), &choices), (std::vector<int>{1}));
  EXPECT_EQ(choices[1], "robocore");
  // An iteration without kernel work leaves the choice where it is.
  EXPECT_EQ(s.Choose(IterationObservation{}), "robocore");
  EXPECT_THROW(s.Choose({true, 5.0, {1.0, 2.0}}), std::invalid_argument) << "one cost per candidate";
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
