#pragma once
// Replays a kernel record's node fetches through the cache hierarchy in the
// order a backend issues them, and keeps what its cost model needs.
//
// Placement and order (shared by every backend): warps are 32 consecutive
// queries; blocks of gpu.warps_per_block warps are dealt to SMs
// round-robin. Each SM runs its warps in waves of `warps_per_wave` (SIMT:
// the resident warps; RT unit: the warp buffer) whose fetches interleave
// step by step, oldest warp first. That is the order a greedy-then-oldest
// scheduler produces when every warp stalls at every node fetch, which the
// ray-cast kernels do (each step's address depends on the previous step).
// SMs advance wave by wave in lockstep, so the shared L2 sees their
// requests interleaved.
//
// Two access patterns:
//   coalesced (SIMT)  per warp step, the active lanes' nodes are merged into
//                     unique 32-byte sectors, one request each; the step
//                     waits for its slowest sector.
//   per thread (TTA+, RoboCore)  every thread's node fetch is its own
//                     request (artifact: -gpgpu_rt_coalesce_warps 0); a
//                     second request to a sector hits in L1.
// A node wider than a sector requests each of its sectors; its latency is
// its slowest sector's.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "backends/gpu_params.h"
#include "backends/warp_nodes.h"
#include "common/uninitialized_vector.h"
#include "robocore/exit_profile.h"
#include "robocore/kernel_record.h"

namespace rc {

struct AccessPattern {
  int warps_per_wave = 1;
  bool coalesced = false;
};

struct MemoryCounters {
  std::uint64_t sector_requests = 0;  // requests to L1, 32 bytes each
  std::uint64_t l1_hits = 0;
  std::uint64_t l2_accesses = 0;  // L1 misses
  std::uint64_t l2_hits = 0;
  std::uint64_t dram_accesses = 0;  // L2 misses, one sector each
  MemoryCounters& operator+=(const MemoryCounters& more);
};

// Per warp or per query: the replay writes every entry (no zero fill
// first, a pass over megabytes per record).
using MemoryCycles = UninitializedVector<std::uint64_t>;

struct MemoryProfile {
  // Coalesced: per warp, the sum over its steps of the slowest sector.
  MemoryCycles warp_memory_cycles;
  // Per thread: per query, the sum of its fetches' latencies.
  MemoryCycles query_memory_cycles;
  std::vector<std::uint64_t> sm_sector_requests;  // per SM
  MemoryCounters totals;
  std::string l1_model;
  std::string l2_model;
};

// The SM a warp runs on.
int SmOfWarp(std::size_t warp, const GpuParams& gpu);
// Each SM's warps, in launch order: warp w is on SmOfWarp(w).
std::vector<std::vector<std::uint32_t>> WarpsBySm(std::size_t warps, const GpuParams& gpu);
std::size_t WarpCount(const KernelRecord& record, const GpuParams& gpu);

MemoryProfile ReplayMemory(const KernelRecord& record, const GpuParams& gpu, const AccessPattern& pattern);
// The same with the record's warp node counts for gpu.warp_size already
// counted (CountWarpNodes).
MemoryProfile ReplayMemory(const KernelRecord& record, const GpuParams& gpu, const AccessPattern& pattern,
                           const WarpNodeCounts& warp_nodes);

// The record's exit profile (robocore/exit_profile.h): its tallied exits
// when the recorder kept them so, else tallied from its exits.
ExitProfile ProfileExits(const KernelRecord& record);

}  // namespace rc
