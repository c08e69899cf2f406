#pragma once
// Shared work of several backends pricing one record (PriceAll, backend.h):
//   Memory     the memory replay, which depends only on the GPU's memory
//              system and the access pattern, so TTA+, TTA+-p, TTA+-cr and
//              RoboCore (same pattern) replay it once;
//   Exits, WarpNodes
//              the exit profile and the warps' node counts (per warp size),
//              which depend on the record alone;
//   UnitWarps  the RT units' per-warp slowest query and per-SM passes
//              (rt_warp_cycles.h), one pass over the queries for every unit
//              whose costs were announced (ExpectUnitWarps) before the first
//              unit asked.
// Thread-safe: the first caller of a profile computes it while later
// callers of the same one wait for it, and callers of different profiles run
// at once. What was announced (ExpectMemory, ExpectUnitWarps) may also be
// computed ahead, all of it at once (ComputeExpected), before the backends
// ask. A result never depends on what else was asked, announced or computed
// ahead. The record must outlive the context and stay unchanged.
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "backends/gpu_params.h"
#include "backends/memory_replay.h"
#include "backends/rt_warp_cycles.h"
#include "backends/warp_nodes.h"
#include "robocore/kernel_record.h"

namespace rc {

class PricingContext {
 public:
  explicit PricingContext(const KernelRecord& record) : record_(record) {}
  const KernelRecord& record() const { return record_; }
  std::shared_ptr<const MemoryProfile> Memory(const GpuParams& gpu, const AccessPattern& pattern);
  std::shared_ptr<const ExitProfile> Exits();
  std::shared_ptr<const WarpNodeCounts> WarpNodes(int warp_size);

  // A backend that will ask Memory(gpu, pattern) says so first, so that
  // ComputeExpected replays it beside the others.
  void ExpectMemory(const GpuParams& gpu, const AccessPattern& pattern);
  // A unit that will ask UnitWarps(gpu, pattern, exits, costs) says so
  // first, so that one pass serves it and the others announced with it
  // (and expects Memory(gpu, pattern)).
  void ExpectUnitWarps(const GpuParams& gpu, const AccessPattern& pattern, int exits, const RayPassCosts& costs);
  // Computes everything announced so far, in an order that keeps every
  // thread busy: the warps' node counts, then the memory replays at once
  // (an OpenMP task each, the longest first; a thread whose replay ends
  // first takes SMs of another's sampled estimate), then each units' pass with
  // its SMs spread over the threads. Left to the backends' own calls, a
  // replay and the pass that needs it ran on one thread while the others
  // waited for them. Called outside a parallel region for that (inside one,
  // it runs on the calling thread). A computation that fails keeps its
  // exception for the backend that asks for its result.
  void ComputeExpected();
  // The warps' cycles under `costs` with the memory cycles of
  // Memory(gpu, pattern): from the exit per query of a ray record, from
  // Exits() for any other.
  std::shared_ptr<const UnitWarpCycles> UnitWarps(const GpuParams& gpu, const AccessPattern& pattern, int exits,
                                                  const RayPassCosts& costs);

 private:
  template <class T>
  using Pending = std::shared_future<std::shared_ptr<const T>>;
  // The units one pass priced, and their cycles in the same order.
  struct UnitWarpGroup {
    std::vector<RayPassCosts> costs;
    std::vector<std::shared_ptr<const UnitWarpCycles>> cycles;
  };
  struct ExpectedMemory {
    GpuParams gpu;
    AccessPattern pattern;
  };
  struct ExpectedUnitWarps {
    GpuParams gpu;
    AccessPattern pattern;
    int exits = 0;
    std::vector<RayPassCosts> costs;  // in the order announced
  };
  const KernelRecord& record_;
  std::mutex mutex_;
  std::map<std::string, ExpectedMemory> expected_memory_;
  std::map<std::string, Pending<MemoryProfile>> profiles_;
  std::map<std::string, Pending<ExitProfile>> exits_;
  std::map<std::string, Pending<WarpNodeCounts>> warp_nodes_;
  std::map<std::string, ExpectedUnitWarps> expected_unit_warps_;
  std::map<std::string, Pending<UnitWarpGroup>> unit_warp_groups_;
};

}  // namespace rc
