#pragma once
// What the RT-unit model (rt_unit_model.h) needs of a ray record per warp
// and per SM, for several units' costs in one pass over the queries
// (ray_query_cycles.h): each warp's slowest query, and each SM's loop
// passes by exit. PricingContext::RayWarps shares the pass between the
// units pricing one record.
#include <cstdint>
#include <vector>

#include "backends/gpu_params.h"
#include "backends/memory_replay.h"
#include "backends/ray_query_cycles.h"
#include "robocore/kernel_record.h"

namespace rc {

struct RayWarpCycles {
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
std::vector<RayWarpCycles> CountRayWarpCycles(const KernelRecord& record, const GpuParams& gpu, int exits,
                                              const MemoryCycles& memory_cycles,
                                              const std::vector<RayPassCosts>& costs);

}  // namespace rc
