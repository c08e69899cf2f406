#include "backends/memory_replay.h"

#include <algorithm>
#include <sstream>

#include "backends/cache_model.h"

namespace rc {
namespace {

class Replayer {
 public:
  Replayer(const KernelRecord& record, const GpuParams& gpu, const AccessPattern& pattern,
           MemoryProfile& profile)
      : record_(record),
        gpu_(gpu),
        pattern_(pattern),
        profile_(profile),
        caches_(gpu, record.footprint_begin(), std::max(record.footprint_end(), record.footprint_begin())) {
    profile_.l1_model = caches_.l1_model();
    profile_.l2_model = caches_.l2_model();
  }

  void Run() {
    const std::size_t n = record_.query_count();
    const std::size_t warps = WarpCount(record_, gpu_);
    std::vector<std::vector<std::uint32_t>> sm_warps(gpu_.sms);
    steps_.assign(warps, 0);
    for (std::size_t w = 0; w < warps; ++w) {
      sm_warps[SmOfWarp(w, gpu_)].push_back(static_cast<std::uint32_t>(w));
      for (std::size_t q = w * gpu_.warp_size; q < std::min(n, (w + 1) * gpu_.warp_size); ++q)
        steps_[w] = std::max(steps_[w], record_.nodes(q));
    }
    profile_.sm_sector_requests.assign(gpu_.sms, 0);
    if (pattern_.coalesced)
      profile_.warp_memory_cycles.assign(warps, 0);
    else
      profile_.query_memory_cycles.assign(n, 0);
    const std::size_t wave = static_cast<std::size_t>(std::max(1, pattern_.warps_per_wave));
    std::size_t rounds = 0;
    for (const auto& list : sm_warps) rounds = std::max(rounds, (list.size() + wave - 1) / wave);
    for (std::size_t r = 0; r < rounds; ++r)
      for (int sm = 0; sm < gpu_.sms; ++sm) {
        const auto& list = sm_warps[sm];
        const std::size_t lo = r * wave;
        if (lo >= list.size()) continue;
        ReplayWave(sm, list.data() + lo, std::min(wave, list.size() - lo));
      }
  }

 private:
  // One sector request; returns its latency.
  int Request(int sm, std::uint64_t sector) {
    const MemoryLevel level = caches_.Access(sm, sector * gpu_.sector_bytes);
    MemoryCounters& c = profile_.totals;
    ++c.sector_requests;
    ++profile_.sm_sector_requests[sm];
    switch (level) {
      case MemoryLevel::kL1: ++c.l1_hits; break;
      case MemoryLevel::kL2: ++c.l2_accesses; ++c.l2_hits; break;
      case MemoryLevel::kDram: ++c.l2_accesses; ++c.dram_accesses; break;
    }
    return caches_.LatencyCycles(level);
  }

  void ReplayWave(int sm, const std::uint32_t* warps, std::size_t count) {
    const std::size_t n = record_.query_count();
    const std::uint64_t sector_bytes = static_cast<std::uint64_t>(gpu_.sector_bytes);
    const std::uint64_t node_bytes = record_.node_bytes;
    std::uint32_t max_steps = 0;
    for (std::size_t i = 0; i < count; ++i) max_steps = std::max(max_steps, steps_[warps[i]]);
    for (std::uint32_t k = 0; k < max_steps; ++k) {
      for (std::size_t i = 0; i < count; ++i) {
        const std::uint32_t w = warps[i];
        if (k >= steps_[w]) continue;
        const std::size_t lo = static_cast<std::size_t>(w) * gpu_.warp_size;
        const std::size_t hi = std::min(n, lo + gpu_.warp_size);
        sectors_.clear();
        for (std::size_t q = lo; q < hi; ++q) {
          if (k >= record_.nodes(q)) continue;
          const std::uint64_t address = record_.fetch_addresses[record_.fetch_offsets[q] + k];
          const std::uint64_t first = address / sector_bytes;
          const std::uint64_t last = (address + node_bytes - 1) / sector_bytes;
          if (pattern_.coalesced) {
            for (std::uint64_t s = first; s <= last; ++s)
              if (std::find(sectors_.begin(), sectors_.end(), s) == sectors_.end())
                sectors_.push_back(s);
          } else {
            int slowest = 0;
            for (std::uint64_t s = first; s <= last; ++s) slowest = std::max(slowest, Request(sm, s));
            profile_.query_memory_cycles[q] += static_cast<std::uint64_t>(slowest);
          }
        }
        if (pattern_.coalesced) {
          int slowest = 0;
          for (std::uint64_t s : sectors_) slowest = std::max(slowest, Request(sm, s));
          profile_.warp_memory_cycles[w] += static_cast<std::uint64_t>(slowest);
        }
      }
    }
  }

  const KernelRecord& record_;
  const GpuParams& gpu_;
  const AccessPattern& pattern_;
  MemoryProfile& profile_;
  CacheHierarchy caches_;
  std::vector<std::uint32_t> steps_;  // per warp: its slowest lane's node count
  std::vector<std::uint64_t> sectors_;
};

std::string MemoryKey(const GpuParams& g, const AccessPattern& p) {
  std::ostringstream key;
  key << g.sms << ' ' << g.warp_size << ' ' << g.warps_per_block << ' ' << g.sector_bytes << ' '
      << g.line_bytes << ' ' << g.l1_bytes << ' ' << g.l1_latency_cycles << ' ' << g.l2_bytes << ' '
      << g.l2_ways << ' ' << g.l2_latency_cycles << ' ' << g.DramExtraCycles() << " | "
      << p.warps_per_wave << ' ' << p.coalesced;
  return key.str();
}

}  // namespace

int SmOfWarp(std::size_t warp, const GpuParams& gpu) {
  return static_cast<int>((warp / static_cast<std::size_t>(gpu.warps_per_block)) %
                          static_cast<std::size_t>(gpu.sms));
}

std::size_t WarpCount(const KernelRecord& record, const GpuParams& gpu) {
  const std::size_t w = static_cast<std::size_t>(gpu.warp_size);
  return (record.query_count() + w - 1) / w;
}

MemoryProfile ReplayMemory(const KernelRecord& record, const GpuParams& gpu,
                           const AccessPattern& pattern) {
  MemoryProfile profile;
  Replayer(record, gpu, pattern, profile).Run();
  return profile;
}

std::shared_ptr<const MemoryProfile> PricingContext::Memory(const GpuParams& gpu,
                                                           const AccessPattern& pattern) {
  const std::string key = MemoryKey(gpu, pattern);
  std::lock_guard<std::mutex> lock(mutex_);
  auto it = profiles_.find(key);
  if (it == profiles_.end())
    it = profiles_.emplace(key, std::make_shared<const MemoryProfile>(ReplayMemory(record_, gpu, pattern)))
             .first;
  return it->second;
}

}  // namespace rc
