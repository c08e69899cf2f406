#pragma once
// The determinism check of the filter's tests: two runs with the same seed
// (at different thread counts) must agree to the bit in every per-record
// output.
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>

#include "workloads/delibot/delibot_run.h"

namespace rc::test {

inline void ExpectSameRows(const DelibotResult& one, const DelibotResult& two) {
  ASSERT_EQ(one.rows.size(), two.rows.size());
  for (std::size_t i = 0; i < one.rows.size(); ++i) {
    EXPECT_EQ(one.rows[i].estimate.x, two.rows[i].estimate.x) << i;
    EXPECT_EQ(one.rows[i].estimate.y, two.rows[i].estimate.y) << i;
    EXPECT_EQ(one.rows[i].estimate.theta, two.rows[i].estimate.theta) << i;
    EXPECT_EQ(one.rows[i].ess, two.rows[i].ess) << i;
    EXPECT_EQ(one.rows[i].nodes, two.rows[i].nodes) << i;
    EXPECT_EQ(one.rows[i].injected, two.rows[i].injected) << i;
    EXPECT_EQ(one.rows[i].hypotheses_alive, two.rows[i].hypotheses_alive) << i;
    EXPECT_EQ(one.rows[i].particles, two.rows[i].particles) << i;
    EXPECT_EQ(one.rows[i].claim_audit, two.rows[i].claim_audit) << i;
    if (!std::isnan(one.rows[i].claim_audit_margin_nats) || !std::isnan(two.rows[i].claim_audit_margin_nats)) {
      EXPECT_EQ(one.rows[i].claim_audit_margin_nats, two.rows[i].claim_audit_margin_nats) << i;
    }
  }
}

}  // namespace rc::test
