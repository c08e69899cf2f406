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
  return Once(mutex_, exits_, "exits", [&] { return ProfileExits(record_); });
}

std::shared_ptr<const WarpNodeCounts> PricingContext::WarpNodes(int warp_size) {
  if (warp_size < 1) throw std::invalid_argument("PricingContext::WarpNodes: warp_size must be at least 1");
  return Once(mutex_, warp_nodes_, std::to_string(warp_size),
              [&] { return CountWarpNodes(record_.fetch_offsets, static_cast<std::size_t>(warp_size)); });
}

void PricingContext::ExpectRayWarps(const GpuParams& gpu, const AccessPattern& pattern, int exits,
                                    const RayPassCosts& costs) {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<RayPassCosts>& expected = expected_rays_[MemoryKey(gpu, pattern) + " | " + std::to_string(exits)];
  if (std::find(expected.begin(), expected.end(), costs) == expected.end()) expected.push_back(costs);
}

std::shared_ptr<const RayWarpCycles> PricingContext::RayWarps(const GpuParams& gpu, const AccessPattern& pattern,
                                                              int exits, const RayPassCosts& costs) {
  const std::string key = MemoryKey(gpu, pattern) + " | " + std::to_string(exits);
  const auto group = Once(mutex_, ray_groups_, key, [&] {
    RayWarpGroup g;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      g.costs = expected_rays_[key];
    }
    if (std::find(g.costs.begin(), g.costs.end(), costs) == g.costs.end()) g.costs.push_back(costs);
    for (RayWarpCycles& c : CountRayWarpCycles(record_, gpu, exits, Memory(gpu, pattern)->query_memory_cycles, g.costs))
      g.cycles.push_back(std::make_shared<const RayWarpCycles>(std::move(c)));
    return g;
  });
  for (std::size_t k = 0; k < group->costs.size(); ++k)
    if (group->costs[k] == costs) return group->cycles[k];
  // Announced after the pass (or never): a pass of its own.
  return std::make_shared<const RayWarpCycles>(
      std::move(CountRayWarpCycles(record_, gpu, exits, Memory(gpu, pattern)->query_memory_cycles, {costs}).front()));
}

}  // namespace rc
