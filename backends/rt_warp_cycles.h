#pragma once
// What the RT-unit model (rt_unit_model.h) needs of a record per warp and
// per SM, for several units' costs in one pass over the queries: each
// warp's slowest query, and each SM's loop passes by exit. A ray record
// keeps one exit per query (ray_query_cycles.h); other records are priced
// by their exit profile (exit_profile.h). PricingContext::UnitWarps shares
// the pass between the units pricing one record: they read the same arrays
// and differ only in their costs.
#include <cstdint>
#include <vector>

#include "backends/gpu_params.h"
#include "backends/memory_replay.h"
#include "backends/ray_query_cycles.h"
#include "robocore/exit_profile.h"
#include "robocore/kernel_record.h"

namespace rc {

struct UnitWarpCycles {
  std::vector<std::uint64_t> slowest;  // per warp, in launch order: its slowest query's cycles
  // Per SM, exits + 1 counts: its quiet passes, then its passes that ended
  // at RETURN_IF j (j < exits). The same under any costs.
  std::vector<std::uint64_t> sm_passes;
};

// Element k of the result is for costs[k] (any number of costs, counted
// kMaxRayCostsPerPass at a time); `exits` is the RETURN_IFs of their
// lowered loop (RayQueryArrays::exits), the same for all of them. The record
// keeps an exit per query (exits_per_query()); memory_cycles has one entry
// per query.
std::vector<UnitWarpCycles> CountRayWarpCycles(const KernelRecord& record, const GpuParams& gpu, int exits,
                                               const MemoryCycles& memory_cycles,
                                               const std::vector<RayPassCosts>& costs);

// The same for a record priced by its exit profile (`profile`, one entry
// per query): a query costs costs[k].once_cycles, its memory cycles, and
// each pass at its variant's cycles (variant 0 a quiet pass, 1 + j
// last_pass_cycles[j]); a query without nodes costs the first two. Any
// number of costs in one pass; a variant above `exits` is refused.
std::vector<UnitWarpCycles> CountProfileWarpCycles(const KernelRecord& record, const ExitProfile& profile,
                                                   const GpuParams& gpu, int exits, const MemoryCycles& memory_cycles,
                                                   const std::vector<RayPassCosts>& costs);

}  // namespace rc
