#include "backends/pricing_context.h"

#include <algorithm>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace rc {
namespace {

std::string MemoryKey(const GpuParams& g, const AccessPattern& p) {
  std::ostringstream key;
  key << g.sms << ' ' << g.warp_size << ' ' << g.warps_per_block << ' ' << g.sector_bytes << ' ' << g.line_bytes << ' '
      << g.l1_bytes << ' ' << g.l1_latency_cycles << ' ' << g.l2_bytes << ' ' << g.l2_ways << ' ' << g.l2_latency_cycles
      << ' ' << g.DramExtraCycles() << " | " << p.warps_per_wave << ' ' << p.coalesced;
  return key.str();
}

// Finds or starts the computation of `key` in `pending` (under `mutex`);
// the caller that starts it computes it outside the lock, the others wait.
template <class T, class Compute>
std::shared_ptr<const T> Once(std::mutex& mutex,
                              std::map<std::string, std::shared_future<std::shared_ptr<const T>>>& pending,
                              const std::string& key, Compute compute) {
  std::promise<std::shared_ptr<const T>> promise;
  std::shared_future<std::shared_ptr<const T>> future;
  bool mine = false;
  {
    std::lock_guard<std::mutex> lock(mutex);
    auto it = pending.find(key);
    if (it == pending.end()) {
      future = promise.get_future().share();
      pending.emplace(key, future);
      mine = true;
    } else {
      future = it->second;
    }
  }
  if (mine) {
    try {
      promise.set_value(std::make_shared<const T>(compute()));
    } catch (...) {
      promise.set_exception(std::current_exception());
    }
  }
  return future.get();
}

}  // namespace

std::shared_ptr<const MemoryProfile> PricingContext::Memory(const GpuParams& gpu, const AccessPattern& pattern) {
  return Once(mutex_, profiles_, MemoryKey(gpu, pattern),
              [&] { return ReplayMemory(record_, gpu, pattern, *WarpNodes(gpu.warp_size)); });
}

std::shared_ptr<const ExitProfile> PricingContext::Exits() {
  if (record_.tallied_exits) return record_.tallied_exits;  // the recorder's, not copied
  return Once(mutex_, exits_, "exits", [&] { return ProfileExits(record_); });
}

std::shared_ptr<const WarpNodeCounts> PricingContext::WarpNodes(int warp_size) {
  if (warp_size < 1) throw std::invalid_argument("PricingContext::WarpNodes: warp_size must be at least 1");
  return Once(mutex_, warp_nodes_, std::to_string(warp_size),
              [&] { return CountWarpNodes(record_.fetch_offsets, static_cast<std::size_t>(warp_size)); });
}

void PricingContext::ExpectMemory(const GpuParams& gpu, const AccessPattern& pattern) {
  std::lock_guard<std::mutex> lock(mutex_);
  expected_memory_.emplace(MemoryKey(gpu, pattern), ExpectedMemory{gpu, pattern});
}

void PricingContext::ExpectUnitWarps(const GpuParams& gpu, const AccessPattern& pattern, int exits,
                                    const RayPassCosts& costs) {
  std::lock_guard<std::mutex> lock(mutex_);
  expected_memory_.emplace(MemoryKey(gpu, pattern), ExpectedMemory{gpu, pattern});
  ExpectedUnitWarps& expected =
      expected_unit_warps_
          .emplace(MemoryKey(gpu, pattern) + " | " + std::to_string(exits), ExpectedUnitWarps{gpu, pattern, exits, {}})
          .first->second;
  if (std::find(expected.costs.begin(), expected.costs.end(), costs) == expected.costs.end())
    expected.costs.push_back(costs);
}

void PricingContext::ComputeExpected() {
  std::vector<ExpectedMemory> memory;
  std::vector<ExpectedUnitWarps> unit_warps;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const auto& [key, m] : expected_memory_) memory.push_back(m);
    for (const auto& [key, u] : expected_unit_warps_) unit_warps.push_back(u);
  }
  // Each result keeps its computation's exception (Once), which reaches the
  // backend that asks for it; here it is only started.
  auto ahead = [](auto compute) {
    try {
      compute();
    } catch (...) {
    }
  };
  for (const ExpectedMemory& m : memory) ahead([&] { WarpNodes(m.gpu.warp_size); });
  // The per-thread replays first: they take longer than the coalesced ones
  // (every lane's fetch is a request, and the sampled estimate pairs lanes).
  std::stable_sort(memory.begin(), memory.end(), [](const ExpectedMemory& a, const ExpectedMemory& b) {
    return !a.pattern.coalesced && b.pattern.coalesced;
  });
  // One task per replay: a thread whose replay ends first takes SMs of the
  // others' sampled estimates (EstimateUnsampled's tasks).
#pragma omp parallel
#pragma omp single
  for (std::size_t i = 0; i < memory.size(); ++i) {
#pragma omp task default(shared) firstprivate(i)
    ahead([&] { Memory(memory[i].gpu, memory[i].pattern); });
  }
  for (const ExpectedUnitWarps& u : unit_warps)
    if (!u.costs.empty()) ahead([&] { UnitWarps(u.gpu, u.pattern, u.exits, u.costs.front()); });
}

std::shared_ptr<const UnitWarpCycles> PricingContext::UnitWarps(const GpuParams& gpu, const AccessPattern& pattern,
                                                                int exits, const RayPassCosts& costs) {
  auto count = [&](const std::vector<RayPassCosts>& all) {
    const MemoryCycles& memory = Memory(gpu, pattern)->query_memory_cycles;
    if (record_.exits_per_query()) return CountRayWarpCycles(record_, gpu, exits, memory, all);
    return CountProfileWarpCycles(record_, *Exits(), gpu, exits, memory, all);
  };
  const std::string key = MemoryKey(gpu, pattern) + " | " + std::to_string(exits);
  const auto group = Once(mutex_, unit_warp_groups_, key, [&] {
    UnitWarpGroup g;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      const auto expected = expected_unit_warps_.find(key);
      if (expected != expected_unit_warps_.end()) g.costs = expected->second.costs;
    }
    if (std::find(g.costs.begin(), g.costs.end(), costs) == g.costs.end()) g.costs.push_back(costs);
    for (UnitWarpCycles& c : count(g.costs))
      g.cycles.push_back(std::make_shared<const UnitWarpCycles>(std::move(c)));
    return g;
  });
  for (std::size_t k = 0; k < group->costs.size(); ++k)
    if (group->costs[k] == costs) return group->cycles[k];
  // Announced after the pass (or never): a pass of its own.
  return std::make_shared<const UnitWarpCycles>(
      std::move(count({costs}).front()));
}

}  // namespace rc
