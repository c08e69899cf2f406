// The models' reach fitted to the trace (returns_beyond_reach.h): returns
// counted over every beam of every record, no-returns left out; the reach
// widened to the returns' 95th percentile only when more than a quarter lie
// beyond it and --max-range was not given; a note either way.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "workloads/delibot/returns_beyond_reach.h"

namespace rc {
namespace {

SensorTrace TraceOf(const std::vector<std::vector<float>>& scans) {
  SensorTrace t;
  t.geometry.beam_count = static_cast<int>(scans.front().size());
  t.geometry.max_range_m = 80.0;
  for (const auto& ranges : scans) {
    LaserScan s;
    s.ranges_m = ranges;
    t.scans.push_back(s);
  }
  return t;
}

TEST(ReturnsBeyondReachTest, CountsReturnsAtOrBeyondTheReachAndLeavesNoReturnsOut) {
  // 6 returns (80 and 95 are no returns), 3 of them at or beyond 10 m.
  const SensorTrace trace = TraceOf({{2.0f, 10.0f, 80.0f, 35.5f}, {9.85f, 95.0f, 4.0f, 12.0f}});
  InMemoryScanSource scans(trace);
  const ReturnsBeyondReach c = CountReturnsBeyondReach(scans, 10.0);
  EXPECT_EQ(c.returns, 6);
  EXPECT_EQ(c.beyond, 3);
  EXPECT_FLOAT_EQ(c.longest_m, 35.5);
  // Bin edges of 0.1 m: half the returns lie below 9.9 m (2, 4, 9.85),
  // all below 35.6 m.
  EXPECT_NEAR(c.QuantileM(0.5), 9.9, 1e-9);
  EXPECT_NEAR(c.QuantileM(1.0), 35.6, 1e-9);
  LaserScan first;
  ASSERT_TRUE(scans.Next(first)) << "the source must be rewound";
  EXPECT_EQ(first.ranges_m[0], 2.0f);
}

TEST(ReturnsBeyondReachTest, WidensTheReachOnlyWhenNotGivenAndMoreThanAQuarterLieBeyond) {
  // 100 returns: 60 at 5 m, 40 spread over 20-59 m (one per metre).
  std::vector<float> ranges(60, 5.0f);
  for (int k = 0; k < 40; ++k) ranges.push_back(20.0f + static_cast<float>(k));
  const SensorTrace trace = TraceOf({ranges});
  InMemoryScanSource scans(trace);
  const ReturnsBeyondReach c = CountReturnsBeyondReach(scans, 10.0);
  ASSERT_EQ(c.returns, 100);
  double reach = 10.0;
  const std::string note = FitReachToTrace(reach, c, false);
  // The 95th return is the one at 54 m: its bin ends at 54.1 m.
  EXPECT_NEAR(reach, 54.1, 1e-9);
  EXPECT_NE(note.find("40% of the trace's returns lie beyond 10 m: the models reach 54.1 m"), std::string::npos)
      << note;
  // Given, the reach is the user's; the note says what it leaves out.
  reach = 10.0;
  const std::string given = FitReachToTrace(reach, c, true);
  EXPECT_EQ(reach, 10.0);
  EXPECT_NE(given.find("40% of the trace's returns lie at or beyond --max-range 10 m (the longest 59.0 m)"),
            std::string::npos)
      << given;
  // A reach that already covers them: nothing to fit or say.
  reach = 60.0;
  EXPECT_EQ(FitReachToTrace(reach, CountReturnsBeyondReach(scans, 60.0), false), "");
  EXPECT_EQ(reach, 60.0);
}

TEST(ReturnsBeyondReachTest, QuietUpToTheThreshold) {
  ReturnsBeyondReach c;
  c.returns = 100;
  c.beyond = static_cast<long>(kBeyondReachFraction * 100);
  c.bins.assign(10, 10);
  double reach = 10.0;
  EXPECT_EQ(FitReachToTrace(reach, c, false), "");
  EXPECT_EQ(reach, 10.0);
  ++c.beyond;
  EXPECT_NE(FitReachToTrace(reach, c, false), "");
  reach = 10.0;
  EXPECT_EQ(FitReachToTrace(reach, ReturnsBeyondReach{}, false), "") << "no returns at all";
}

}  // namespace
}  // namespace rc
