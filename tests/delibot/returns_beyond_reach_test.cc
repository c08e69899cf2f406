// The note on returns beyond the models' reach (returns_beyond_reach.h):
// counted over every beam of every record, no-returns left out, and said
// only above its threshold.
#include <string>

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
  const SensorTrace trace = TraceOf({{2.0f, 10.0f, 80.0f, 35.5f}, {9.9f, 95.0f, 4.0f, 12.0f}});
  InMemoryScanSource scans(trace);
  const ReturnsBeyondReach c = CountReturnsBeyondReach(scans, 10.0);
  EXPECT_EQ(c.returns, 6);
  EXPECT_EQ(c.beyond, 3);
  EXPECT_FLOAT_EQ(c.longest_m, 35.5);
  LaserScan first;
  ASSERT_TRUE(scans.Next(first)) << "the source must be rewound";
  EXPECT_EQ(first.ranges_m[0], 2.0f);
  // Half the returns beyond 10 m: noted, with the numbers.
  const std::string note = BeyondReachNote(c, 10.0);
  EXPECT_NE(note.find("50% of the trace's returns"), std::string::npos) << note;
  EXPECT_NE(note.find("--max-range 10 m (the longest 35.5 m)"), std::string::npos) << note;
  // A reach of 36 m covers them all: nothing to say.
  EXPECT_EQ(BeyondReachNote(CountReturnsBeyondReach(scans, 36.0), 36.0), "");
}

TEST(ReturnsBeyondReachTest, QuietUpToTheThreshold) {
  ReturnsBeyondReach c;
  c.returns = 100;
  c.beyond = static_cast<long>(kBeyondReachNoteFraction * 100);
  EXPECT_EQ(BeyondReachNote(c, 10.0), "");
  ++c.beyond;
  EXPECT_NE(BeyondReachNote(c, 10.0), "");
  EXPECT_EQ(BeyondReachNote(ReturnsBeyondReach{}, 10.0), "") << "no returns at all";
}

}  // namespace
}  // namespace rc
