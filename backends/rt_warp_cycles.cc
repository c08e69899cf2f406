#include "backends/rt_warp_cycles.h"

#include <algorithm>
#include <cstdint>
#include <stdexcept>

#include "backends/memory_replay.h"

namespace rc {
namespace {

// Each unit's counts before a pass: no warp's slowest query yet, no pass on
// any SM (variants per SM).
std::vector<UnitWarpCycles> ZeroUnitWarpCycles(std::size_t units, std::size_t warps, const GpuParams& gpu,
                                               std::size_t variants) {
  std::vector<UnitWarpCycles> out(units);
  for (UnitWarpCycles& c : out) {
    c.slowest.assign(warps, 0);
    c.sm_passes.assign(static_cast<std::size_t>(gpu.sms) * variants, 0);
  }
  return out;
}

}  // namespace

std::vector<UnitWarpCycles> CountRayWarpCycles(const KernelRecord& record, const GpuParams& gpu, int exits,
                                               const MemoryCycles& memory_cycles,
                                               const std::vector<RayPassCosts>& costs) {
  const std::size_t n = record.query_count();
  if (!record.exits_per_query()) throw std::logic_error("CountRayWarpCycles: the record keeps no exit per query");
  if (memory_cycles.size() != n) throw std::logic_error("CountRayWarpCycles: memory cycles for another record");
  if (exits < 0 || exits > 255) throw std::logic_error("CountRayWarpCycles: exits must be 0 to 255");
  const std::size_t warps = WarpCount(record, gpu);
  const std::size_t per_sm = static_cast<std::size_t>(exits) + 1;
  std::vector<UnitWarpCycles> out = ZeroUnitWarpCycles(costs.size(), warps, gpu, per_sm);
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

namespace {

// One SM's warps under up to kLanes units side by side: the lanes' loops
// have a fixed width, which the compiler unrolls into vectors, and lanes
// past the units' count cost 0. pass_cycles holds a pass's cycles by
// variant, kLanes per variant (pass counts and a pass's cycles fit 32 bits;
// their products are 64). Writes each unit's slowest query per warp;
// returns the SM's passes by variant.
template <int kLanes>
std::vector<std::uint64_t> ProfileSmWarps(const ExitProfile& profile, const MemoryCycles& memory_cycles,
                                          const std::vector<std::uint32_t>& warps, const GpuParams& gpu,
                                          std::size_t n, std::size_t variants, const std::uint64_t* once,
                                          const std::uint32_t* pass_cycles, int count, UnitWarpCycles* out) {
  const std::uint32_t* offsets = profile.offsets.data();
  const std::uint8_t* variant = profile.variant.data();
  const std::uint32_t* passes = profile.passes.data();
  std::vector<std::uint64_t> sm_passes(variants, 0);
  for (std::uint32_t w : warps) {
    const std::size_t lo = static_cast<std::size_t>(w) * gpu.warp_size;
    const std::size_t hi = std::min(n, lo + gpu.warp_size);
    std::uint64_t slowest[kLanes] = {};
    for (std::size_t q = lo; q < hi; ++q) {
      std::uint64_t cycles[kLanes];
      for (int k = 0; k < kLanes; ++k) cycles[k] = once[k] + memory_cycles[q];
      for (std::uint32_t i = offsets[q]; i < offsets[q + 1]; ++i) {
        const std::uint64_t p = passes[i];
        const std::uint32_t* c = pass_cycles + std::size_t{variant[i]} * kLanes;
        sm_passes[variant[i]] += p;
        for (int k = 0; k < kLanes; ++k) cycles[k] += p * c[k];
      }
      for (int k = 0; k < kLanes; ++k) slowest[k] = std::max(slowest[k], cycles[k]);
    }
    for (int k = 0; k < count; ++k) out[k].slowest[w] = slowest[k];
  }
  return sm_passes;
}

}  // namespace

std::vector<UnitWarpCycles> CountProfileWarpCycles(const KernelRecord& record, const ExitProfile& profile,
                                                   const GpuParams& gpu, int exits, const MemoryCycles& memory_cycles,
                                                   const std::vector<RayPassCosts>& costs) {
  const std::size_t n = record.query_count();
  if (profile.offsets.size() != n + 1) throw std::logic_error("CountProfileWarpCycles: exit profile of another record");
  if (memory_cycles.size() != n) throw std::logic_error("CountProfileWarpCycles: memory cycles for another record");
  if (exits < 0 || exits > 255) throw std::logic_error("CountProfileWarpCycles: exits must be 0 to 255");
  if (!profile.variant.empty() && *std::max_element(profile.variant.begin(), profile.variant.end()) > exits)
    throw std::logic_error("CountProfileWarpCycles: the profile has an exit the program's loop does not");
  const std::size_t warps = WarpCount(record, gpu);
  const std::size_t variants = static_cast<std::size_t>(exits) + 1;
  std::vector<UnitWarpCycles> out = ZeroUnitWarpCycles(costs.size(), warps, gpu, variants);
  const std::vector<std::vector<std::uint32_t>> sm_warps = WarpsBySm(warps, gpu);
  for (std::size_t first = 0; first < costs.size(); first += kMaxRayCostsPerPass) {
    const int count = static_cast<int>(std::min<std::size_t>(kMaxRayCostsPerPass, costs.size() - first));
    // Four lanes serve the four RT units pricing a record; eight the rest.
    const int lanes = count <= 4 ? 4 : kMaxRayCostsPerPass;
    std::uint64_t once[kMaxRayCostsPerPass] = {};
    for (int k = 0; k < count; ++k) once[k] = costs[first + k].once_cycles;
    std::vector<std::uint32_t> pass_cycles(variants * static_cast<std::size_t>(lanes), 0);
    for (std::size_t v = 0; v < variants; ++v)
      for (int k = 0; k < count; ++k) {
        const RayPassCosts& c = costs[first + k];
        const std::uint64_t cycles = v == 0 ? c.quiet_pass_cycles : c.last_pass_cycles[v - 1];
        if (cycles > UINT32_MAX) throw std::logic_error("CountProfileWarpCycles: a pass of more than 2^32 cycles");
        pass_cycles[v * static_cast<std::size_t>(lanes) + static_cast<std::size_t>(k)] =
            static_cast<std::uint32_t>(cycles);
      }
#pragma omp parallel for schedule(dynamic, 1)
    for (int sm = 0; sm < gpu.sms; ++sm) {
      const std::vector<std::uint64_t> sm_passes =
          lanes == 4 ? ProfileSmWarps<4>(profile, memory_cycles, sm_warps[sm], gpu, n, variants, once,
                                         pass_cycles.data(), count, out.data() + first)
                     : ProfileSmWarps<kMaxRayCostsPerPass>(profile, memory_cycles, sm_warps[sm], gpu, n, variants,
                                                           once, pass_cycles.data(), count, out.data() + first);
      for (int k = 0; k < count; ++k)
        std::copy(sm_passes.begin(), sm_passes.end(),
                  out[first + k].sm_passes.begin() + static_cast<long>(static_cast<std::size_t>(sm) * variants));
    }
  }
  return out;
}

}  // namespace rc
