#pragma once
// Which launches of a split batch are recorded and priced.
//
// A batch above a workload's launch limit runs as several launches
// (DeliBot: kMaxRaysPerLaunch, workloads/delibot/sensor_model.h). Its full
// launches (every one but the last, which holds the remainder) have the
// same number of queries and, for a batch whose queries are drawn alike
// (the uniform first set of global localization), the same distribution of
// work. A launch sample records and prices at most `priced` of them, spread
// evenly over the batch (launch i of F is priced when (i * priced) mod F <
// priced, as AddressSample spreads SMs: launch 0 for one, launches 0 and
// F/2 for two, ...); the others are cast without a record and priced as
// the mean of the priced ones (BackendLedger::AddLaunchesLike). The last
// launch is always recorded and priced. Every functional answer is the
// same: only the pricing of the unrecorded launches is estimated.
#include <cstddef>
#include <cstdint>

#include "common/parameter_spec.h"

namespace rc {

// Full launches of one split batch that are priced, at most (0: every one).
// Each priced launch costs about what casting it costs again (recording and
// the cost models). Measured against pricing every launch: on the demo's
// first update under the beam model (24 full launches of about a million
// rays), every backend's cycles within 0.32% at 1, 2, 4 or 8 priced
// launches; on launches of 65,520 rays, within 1.4% at 4, where the SM
// sample's estimate of one launch varies by about 1% from launch to launch
// (docs/pricing.md, "Sampled launches"; the SM sample's own error is
// bounded at 3.5%, tests/backends/sampled_pricing_test.cc). Four: a few
// launches, so that no single launch's estimate sets the batch's price.
inline constexpr int kPricedLaunchesPerBatch = 4;
inline constexpr ParameterSpec kPricedLaunchesPerBatchSpec{
    "launches", 0, 1 << 20,
    "assumption: the launches of a split batch are drawn alike; error measured in docs/pricing.md (\"Sampled "
    "launches\") and bounded by tests/delibot/mcl_components_test.cc"};
static_assert(kPricedLaunchesPerBatchSpec.min <= kPricedLaunchesPerBatch &&
              kPricedLaunchesPerBatch <= kPricedLaunchesPerBatchSpec.max);

struct LaunchSample {
  int priced = kPricedLaunchesPerBatch;  // 0 (or >= the full launches): every launch

  // Whether full launch `launch` of `full_launches` is recorded and priced.
  bool Prices(std::size_t launch, std::size_t full_launches) const {
    if (priced <= 0 || static_cast<std::size_t>(priced) >= full_launches) return true;
    return (launch * static_cast<std::size_t>(priced)) % full_launches < static_cast<std::size_t>(priced);
  }
};

// The full launches of one batch that a launch sample left unrecorded:
// `count` launches with these queries and nodes (exact: they were cast),
// priced as the mean of the `like` launches of the same batch that were
// priced just before.
struct EstimatedLaunches {
  std::size_t count = 0;
  std::size_t like = 0;
  std::uint64_t queries = 0;
  std::uint64_t nodes = 0;
};

}  // namespace rc
