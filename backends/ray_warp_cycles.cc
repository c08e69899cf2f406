#include "backends/ray_warp_cycles.h"

#include <algorithm>
#include <stdexcept>

#include "backends/memory_replay.h"

namespace rc {

std::vector<RayWarpCycles> CountRayWarpCycles(const KernelRecord& record, const GpuParams& gpu, int exits,
                                              const MemoryCycles& memory_cycles,
                                              const std::vector<RayPassCosts>& costs) {
  const std::size_t n = record.query_count();
  if (!record.exits_per_query()) throw std::logic_error("CountRayWarpCycles: the record keeps no exit per query");
  if (memory_cycles.size() != n) throw std::logic_error("CountRayWarpCycles: memory cycles for another record");
  if (exits < 0 || exits > 255) throw std::logic_error("CountRayWarpCycles: exits must be 0 to 255");
  const std::size_t warps = WarpCount(record, gpu);
  const std::size_t per_sm = static_cast<std::size_t>(exits) + 1;
  std::vector<RayWarpCycles> out(costs.size());
  for (RayWarpCycles& c : out) {
    c.slowest.assign(warps, 0);
    c.sm_passes.assign(static_cast<std::size_t>(gpu.sms) * per_sm, 0);
  }
  RayQueryArrays arrays;
  arrays.fetch_offsets = record.fetch_offsets.data();
  arrays.last_exits = record.last_exits.data();
  arrays.memory_cycles = memory_cycles.data();
  arrays.exits = exits;
  const std::vector<std::vector<std::uint32_t>> sm_warps = WarpsBySm(warps, gpu);
  for (std::size_t first = 0; first < costs.size(); first += kMaxRayCostsPerPass) {
    const int count = static_cast<int>(std::min<std::size_t>(kMaxRayCostsPerPass, costs.size() - first));
#pragma omp parallel for schedule(dynamic, 1)
    for (int sm = 0; sm < gpu.sms; ++sm) {
      RayPassTally tally;
      std::uint64_t slowest[kMaxRayCostsPerPass];
      for (std::uint32_t w : sm_warps[sm]) {
        const std::size_t lo = static_cast<std::size_t>(w) * gpu.warp_size;
        SlowestRayQueries(arrays, costs.data() + first, count, lo, std::min(n, lo + gpu.warp_size), slowest, tally);
        for (int k = 0; k < count; ++k) out[first + k].slowest[w] = slowest[k];
      }
      for (int k = 0; k < count; ++k) {
        std::uint64_t* passes = out[first + k].sm_passes.data() + static_cast<std::size_t>(sm) * per_sm;
        passes[0] = tally.quiet;
        for (int j = 0; j < exits; ++j) passes[1 + j] = tally.exit[j];
      }
    }
  }
  return out;
}

}  // namespace rc
