#include "backends/memory_replay.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <sstream>

#include "backends/cache_model.h"

namespace rc {
namespace {

// The sector requests one SM issues, in issue order. Each request belongs to
// a group (one node fetch of one thread, or one warp step), whose latency is
// its slowest request's and is charged to the group's owner (the query, or
// the warp). Rounds mark the SM's waves, so the shared L2 can see the SMs'
// requests interleaved wave by wave.
struct SmStream {
  std::vector<std::uint32_t> sectors;    // per request
  std::vector<std::uint32_t> owner;      // per request: its group's query or warp
  std::vector<std::uint8_t> group_start; // per request: 1 if it starts a group
  std::vector<std::uint8_t> level;       // per request: MemoryLevel
  std::vector<std::uint32_t> round_end;  // per wave: one past its last request
  std::vector<std::uint32_t> l1_misses;  // requests that missed L1, in order
};

// Builds one SM's stream: each wave step-major (step 0 of every warp, warps
// and lanes in order, then step 1, ...). The wave's fetches are first sorted
// by step with a counting sort that reads the record sequentially, so the
// step-major walk reads a small buffer, not hundreds of strided streams.
class StreamBuilder {
 public:
  StreamBuilder(const KernelRecord& record, const GpuParams& gpu, const AccessPattern& pattern,
                const CacheHierarchy& caches, const std::vector<std::uint32_t>& steps)
      : record_(record), gpu_(gpu), pattern_(pattern), caches_(caches), steps_(steps) {
    const std::uint32_t b = record.node_bytes;
    one_sector_nodes_ = b > 0 && (b & (b - 1)) == 0 && b <= static_cast<std::uint32_t>(gpu.sector_bytes);
    for (const MemoryRegion& r : record.regions) one_sector_nodes_ = one_sector_nodes_ && r.base % b == 0;
  }

  void Build(const std::vector<std::uint32_t>& warps, SmStream& out) {
    // One request per node fetch, when a node fits a sector (a bound when
    // coalesced); wider nodes grow the arrays as they go.
    std::uint64_t fetches = 0;
    for (std::uint32_t w : warps) {
      const std::size_t lo = static_cast<std::size_t>(w) * gpu_.warp_size;
      const std::size_t hi = std::min(record_.query_count(), lo + gpu_.warp_size);
      fetches += record_.fetch_offsets[hi] - record_.fetch_offsets[lo];
    }
    out.sectors.reserve(fetches);
    out.owner.reserve(fetches);
    out.group_start.reserve(fetches);
    const std::size_t wave = static_cast<std::size_t>(std::max(1, pattern_.warps_per_wave));
    for (std::size_t lo = 0; lo < warps.size(); lo += wave) {
      AddWave(warps.data() + lo, std::min(wave, warps.size() - lo), out);
      out.round_end.push_back(static_cast<std::uint32_t>(out.sectors.size()));
    }
  }

 private:
  void AddWave(const std::uint32_t* warps, std::size_t count, SmStream& out) {
    const std::size_t n = record_.query_count();
    const std::uint64_t* offsets = record_.fetch_offsets.data();
    lane_query_.clear();
    lane_warp_.clear();
    std::uint32_t max_steps = 0;
    for (std::size_t i = 0; i < count; ++i) {
      const std::size_t lo = static_cast<std::size_t>(warps[i]) * gpu_.warp_size;
      for (std::size_t q = lo; q < std::min(n, lo + gpu_.warp_size); ++q) {
        lane_query_.push_back(static_cast<std::uint32_t>(q));
        lane_warp_.push_back(warps[i]);
      }
      max_steps = std::max(max_steps, steps_[warps[i]]);
    }
    // Fetches per step = lanes with more nodes than the step's index.
    step_start_.assign(max_steps + 2, 0);
    for (std::uint32_t q : lane_query_) ++step_start_[offsets[q + 1] - offsets[q]];
    std::uint64_t active = 0;
    for (std::uint32_t k = max_steps + 1; k-- > 0;) {
      const std::uint64_t ending_here = step_start_[k];
      step_start_[k] = active;  // lanes still active at step k
      active += ending_here;
    }
    std::uint64_t total = 0;
    for (std::uint32_t k = 0; k <= max_steps; ++k) {
      const std::uint64_t c = step_start_[k];
      step_start_[k] = total;
      total += c;
    }
    cursor_.assign(step_start_.begin(), step_start_.end());
    const std::uint64_t node_bytes = record_.node_bytes;
    const std::size_t base = out.sectors.size();
    if (!pattern_.coalesced && one_sector_nodes_) {
      // Per thread, one request per fetch: the step-sorted order is the
      // stream itself, so scatter straight into it.
      out.sectors.resize(base + total);
      out.owner.resize(base + total);
      out.group_start.resize(base + total, 1);
      for (std::uint32_t j = 0; j < lane_query_.size(); ++j) {
        const std::uint32_t q = lane_query_[j];
        const std::uint64_t* a = record_.fetch_addresses.data() + offsets[q];
        const std::uint32_t nodes = static_cast<std::uint32_t>(offsets[q + 1] - offsets[q]);
        for (std::uint32_t k = 0; k < nodes; ++k) {
          const std::uint64_t at = base + cursor_[k]++;
          out.sectors[at] = caches_.SectorNumber(a[k]);
          out.owner[at] = q;
        }
      }
      return;
    }
    // General case (coalesced, or nodes wider than a sector): sort by step,
    // then walk the steps, writing at most `span` requests per fetch.
    by_step_address_.resize(total);
    by_step_owner_.resize(total);
    for (std::uint32_t j = 0; j < lane_query_.size(); ++j) {
      const std::uint32_t q = lane_query_[j];
      const std::uint32_t owner = pattern_.coalesced ? lane_warp_[j] : q;
      const std::uint64_t* a = record_.fetch_addresses.data() + offsets[q];
      const std::uint32_t nodes = static_cast<std::uint32_t>(offsets[q + 1] - offsets[q]);
      for (std::uint32_t k = 0; k < nodes; ++k) {
        const std::uint64_t at = cursor_[k]++;
        by_step_address_[at] = a[k];
        by_step_owner_[at] = owner;
      }
    }
    const std::uint64_t span = (node_bytes + gpu_.sector_bytes - 1) / gpu_.sector_bytes + 1;
    out.sectors.resize(base + total * span);
    out.owner.resize(base + total * span);
    out.group_start.resize(base + total * span);
    std::uint32_t* sector_out = out.sectors.data();
    std::uint32_t* owner_out = out.owner.data();
    std::uint8_t* start_out = out.group_start.data();
    std::size_t at = base, group_begin = base;
    for (std::uint32_t k = 0; k < max_steps; ++k) {
      for (std::uint64_t e = step_start_[k]; e < step_start_[k + 1]; ++e) {
        const std::uint32_t owner = by_step_owner_[e];
        // Coalesced: one group per warp step (the warp's lanes are adjacent
        // within a step); per thread: one group per node fetch.
        if (!pattern_.coalesced || e == step_start_[k] || owner != by_step_owner_[e - 1]) {
          group_begin = at;
          ++group_id_;
        }
        const std::uint64_t address = by_step_address_[e];
        const std::uint32_t last = caches_.SectorNumber(address + node_bytes - 1);
        for (std::uint32_t sector = caches_.SectorNumber(address); sector <= last; ++sector) {
          if (pattern_.coalesced && IsRepeat(sector, sector_out + group_begin, sector_out + at)) continue;
          sector_out[at] = sector;
          owner_out[at] = owner;
          start_out[at] = at == group_begin;
          ++at;
        }
      }
    }
    out.sectors.resize(at);
    out.owner.resize(at);
    out.group_start.resize(at);
  }

  // Whether `sector` is already among the current group's requests
  // [begin, end), and remember it. A small table indexed by the sector's
  // hash answers most lookups; a slot taken by another sector of the
  // same group falls back to a scan.
  bool IsRepeat(std::uint32_t sector, const std::uint32_t* begin, const std::uint32_t* end) {
    // Fibonacci hashing: grid rows are a fixed number of sectors apart, so
    // low bits alone would collide.
    Seen& slot = seen_[(sector * 2654435769u) >> (32 - kSeenBits)];
    if (slot.group == group_id_) {
      if (slot.sector == sector) return true;
      if (std::find(begin, end, sector) != end) return true;
    }
    slot = {sector, group_id_};
    return false;
  }

  struct Seen {
    std::uint32_t sector = 0;
    std::uint64_t group = 0;  // 0: never; groups count from 1
  };
  static constexpr int kSeenBits = 6;  // 64 slots for at most 32 lanes per group
  std::array<Seen, 1 << kSeenBits> seen_{};
  std::uint64_t group_id_ = 0;

  const KernelRecord& record_;
  const GpuParams& gpu_;
  const AccessPattern& pattern_;
  const CacheHierarchy& caches_;
  const std::vector<std::uint32_t>& steps_;
  // Every node lies within one sector: a power-of-two size no larger than a
  // sector, at addresses aligned to it (the layouts guarantee it).
  bool one_sector_nodes_ = false;
  std::vector<std::uint32_t> lane_query_, lane_warp_, by_step_owner_;
  std::vector<std::uint64_t> step_start_, cursor_, by_step_address_;
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

// Three phases: (1) per SM, in parallel: build its request stream and run
// it through its own L1; (2) serially: the L1 misses of all SMs through the
// shared L2, wave round by wave round, SMs in order; (3) per SM, in
// parallel: charge each group's slowest latency to its owner. Each SM's
// work is independent and the L2 order is fixed, so the result does not
// depend on the thread count.
MemoryProfile ReplayMemory(const KernelRecord& record, const GpuParams& gpu,
                           const AccessPattern& pattern) {
  MemoryProfile profile;
  CacheHierarchy caches(gpu, record.footprint_begin(),
                        std::max(record.footprint_end(), record.footprint_begin()));
  profile.l1_model = caches.l1_model();
  profile.l2_model = caches.l2_model();

  const std::size_t n = record.query_count();
  const std::size_t warps = WarpCount(record, gpu);
  std::vector<std::vector<std::uint32_t>> sm_warps(gpu.sms);
  std::vector<std::uint32_t> steps(warps, 0);  // per warp: its slowest lane's node count
  for (std::size_t w = 0; w < warps; ++w) {
    sm_warps[SmOfWarp(w, gpu)].push_back(static_cast<std::uint32_t>(w));
    for (std::size_t q = w * gpu.warp_size; q < std::min(n, (w + 1) * gpu.warp_size); ++q)
      steps[w] = std::max(steps[w], record.nodes(q));
  }
  if (pattern.coalesced)
    profile.warp_memory_cycles.assign(warps, 0);
  else
    profile.query_memory_cycles.assign(n, 0);
  std::vector<std::uint64_t>& owner_cycles =
      pattern.coalesced ? profile.warp_memory_cycles : profile.query_memory_cycles;

  std::vector<SmStream> streams(gpu.sms);
#pragma omp parallel for schedule(dynamic, 1)
  for (int sm = 0; sm < gpu.sms; ++sm) {
    SmStream& s = streams[sm];
    StreamBuilder(record, gpu, pattern, caches, steps).Build(sm_warps[sm], s);
    s.level.resize(s.sectors.size());
    // Level 0 = L1 hit; 1 = missed, L2 or DRAM decided below.
    caches.AccessL1(sm, s.sectors.data(), s.sectors.size(), s.level.data(), s.l1_misses);
  }

  std::size_t rounds = 0;
  for (const SmStream& s : streams) rounds = std::max(rounds, s.round_end.size());
  std::vector<std::size_t> next_miss(gpu.sms, 0);
  for (std::size_t r = 0; r < rounds; ++r)
    for (int sm = 0; sm < gpu.sms; ++sm) {
      SmStream& s = streams[sm];
      if (r >= s.round_end.size()) continue;
      std::size_t& m = next_miss[sm];
      for (; m < s.l1_misses.size() && s.l1_misses[m] < s.round_end[r]; ++m) {
        const std::uint32_t i = s.l1_misses[m];
        s.level[i] = caches.AccessL2(s.sectors[i]) ? 1 : 2;
      }
    }

  const int latency[3] = {caches.LatencyCycles(MemoryLevel::kL1),
                          caches.LatencyCycles(MemoryLevel::kL2),
                          caches.LatencyCycles(MemoryLevel::kDram)};
  std::vector<std::array<std::uint64_t, 3>> sm_levels(gpu.sms, {0, 0, 0});
#pragma omp parallel for schedule(dynamic, 1)
  for (int sm = 0; sm < gpu.sms; ++sm) {
    const SmStream& s = streams[sm];
    std::array<std::uint64_t, 3> counts = {0, 0, 0};
    int slowest = 0;
    for (std::size_t i = 0; i < s.sectors.size(); ++i) {
      ++counts[s.level[i]];
      const int l = latency[s.level[i]];
      slowest = s.group_start[i] ? l : std::max(slowest, l);
      // A group ends before the next group's first request: charge it then.
      if (i + 1 == s.sectors.size() || s.group_start[i + 1])
        owner_cycles[s.owner[i]] += static_cast<std::uint64_t>(slowest);  // owners are per SM
    }
    sm_levels[sm] = counts;
  }

  profile.sm_sector_requests.assign(gpu.sms, 0);
  MemoryCounters& c = profile.totals;
  for (int sm = 0; sm < gpu.sms; ++sm) {
    const auto& l = sm_levels[sm];
    profile.sm_sector_requests[sm] = l[0] + l[1] + l[2];
    c.sector_requests += l[0] + l[1] + l[2];
    c.l1_hits += l[0];
    c.l2_accesses += l[1] + l[2];
    c.l2_hits += l[1];
    c.dram_accesses += l[2];
  }
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

ExitProfile ProfileExits(const KernelRecord& record) {
  const std::size_t n = record.query_count();
  const std::uint64_t* offsets = record.fetch_offsets.data();
  const std::uint8_t* exits = record.node_exits.data();
  // Distinct exits of query q: "no exit" first (counted in one vectorized
  // pass: most passes have none), then the rare exits in first-seen order.
  auto tally = [&](std::size_t q, std::uint8_t* variant, std::uint32_t* passes) {
    const std::uint8_t* begin = exits + offsets[q];
    const std::uint8_t* end = exits + offsets[q + 1];
    const auto none = static_cast<std::uint32_t>(std::count(begin, end, kNoExit));
    std::uint32_t distinct = 0;
    if (none > 0) {
      variant[0] = 0;
      passes[0] = none;
      distinct = 1;
    }
    if (none == static_cast<std::uint32_t>(end - begin)) return distinct;
    for (const std::uint8_t* p = begin; p < end; ++p) {
      // Skip whole words of "no exit" (all bits set) at a time.
      std::uint64_t word;
      while (end - p >= 8 && (std::memcpy(&word, p, 8), word == ~std::uint64_t{0})) p += 8;
      if (p == end) break;
      if (*p == kNoExit) continue;
      const auto v = static_cast<std::uint8_t>(1 + *p);
      std::uint32_t i = 0;
      while (i < distinct && variant[i] != v) ++i;
      if (i == distinct) {
        variant[i] = v;
        passes[i] = 0;
        ++distinct;
      }
      ++passes[i];
    }
    return distinct;
  };
  ExitProfile profile;
  profile.offsets.assign(n + 1, 0);
#pragma omp parallel for schedule(static)
  for (long q = 0; q < static_cast<long>(n); ++q) {
    std::uint8_t variant[256];
    std::uint32_t passes[256];
    profile.offsets[q + 1] = tally(static_cast<std::size_t>(q), variant, passes);
  }
  for (std::size_t q = 0; q < n; ++q) profile.offsets[q + 1] += profile.offsets[q];
  profile.variant.resize(profile.offsets[n]);
  profile.passes.resize(profile.offsets[n]);
#pragma omp parallel for schedule(static)
  for (long q = 0; q < static_cast<long>(n); ++q)
    tally(static_cast<std::size_t>(q), profile.variant.data() + profile.offsets[q],
          profile.passes.data() + profile.offsets[q]);
  return profile;
}

std::shared_ptr<const ExitProfile> PricingContext::Exits() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!exits_) exits_ = std::make_shared<const ExitProfile>(ProfileExits(record_));
  return exits_;
}

}  // namespace rc
