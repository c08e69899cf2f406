#include "backends/memory_replay.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include <omp.h>

#include "backends/borrowed_cycles.h"
#include "backends/cache_model.h"
#include "backends/key_ranks.h"
#include "backends/warp_nodes.h"
#include "common/loop_exceptions.h"

namespace rc {
namespace {

// Per thread: the L1 latency of every node fetch of warp w's queries, the
// share of their memory cycles that every fetch pays (`lanes` queries a
// warp).
void WriteL1Cycles(const KernelRecord& record, std::size_t w, std::size_t lanes, std::uint64_t l1_latency,
                   std::uint64_t* query_cycles) {
  const std::size_t n = record.query_count();
  for (std::size_t q = w * lanes; q < std::min(n, (w + 1) * lanes); ++q) query_cycles[q] = l1_latency * record.nodes(q);
}

// What one SM's replay leaves for the shared L2: its L1 misses, in issue
// order, wave by wave, and its request counts. A group (one node fetch of
// one thread, or one warp step) waits for its slowest request. Latencies
// grow level by level (cache_model.h), so a group that hit L1 everywhere
// waits for the L1, and one with a miss waits for its slowest miss: the
// owner is charged the L1 latency per group up front, and the difference
// when the group's last miss has been through the L2.
// The per-miss and per-request buffers below are written in full as they
// grow, so they grow without a zero fill (UninitializedVector).
struct SmMisses {
  UninitializedVector<std::uint32_t> sector;
  UninitializedVector<std::uint32_t> owner;     // the query (per thread) or warp (coalesced)
  UninitializedVector<std::uint8_t> group_end;  // 1 on the last miss of its group
  std::vector<std::uint32_t> wave_end;  // per wave: one past its last miss
  std::uint64_t requests = 0, l2_hits = 0, dram = 0;

  void Reserve(std::size_t misses) {
    sector.reserve(misses);
    owner.reserve(misses);
    group_end.reserve(misses);
  }
};

// Replays one SM's waves through its L1. Each wave runs step-major (step 0
// of every warp, warps and lanes in order, then step 1, ...). The wave's
// fetches are first sorted by step with a counting sort that reads the
// record sequentially, so the step-major walk reads a small buffer, not
// hundreds of strided streams. The wave's buffers are reused wave after
// wave and stay in the host's caches; nothing per request outlives the
// wave except the L1 misses.
class SmReplay {
 public:
  SmReplay(const KernelRecord& record, const GpuParams& gpu, const AccessPattern& pattern, CacheHierarchy& caches,
           int sm, const std::vector<std::uint32_t>& steps, SmMisses& out)
      : record_(record),
        gpu_(gpu),
        coalesced_(pattern.coalesced),
        l1_(caches.L1(sm)),
        begin_(caches.begin()),
        sector_shift_(caches.sector_shift()),
        steps_(steps),
        out_(out) {
    const std::uint32_t b = record.node_bytes;
    one_sector_nodes_ = b > 0 && (b & (b - 1)) == 0 && b <= static_cast<std::uint32_t>(gpu.sector_bytes);
    for (const MemoryRegion& r : record.regions) one_sector_nodes_ = one_sector_nodes_ && r.base % b == 0;
  }

  // The wave made of `count` warps.
  void Wave(const std::uint32_t* warps, std::size_t count) {
    const std::uint32_t max_steps = SortByStep(warps, count);
    if (one_sector_nodes_ && !coalesced_) {
      // Per thread, one sector per fetch: the sorted fetches are the
      // requests, each its own group.
      Grow(misses_, fetches_);
      const std::size_t m = l1_.AccessAll(sector_.data(), fetches_, misses_.data());
      const MissSlots out = AddMisses(m);
      for (std::size_t j = 0; j < m; ++j) {
        out.sector[j] = sector_[misses_[j]];
        out.owner[j] = owner_[misses_[j]];
        out.group_end[j] = 1;
      }
      out_.requests += fetches_;
    } else {
      const std::size_t requests = coalesced_ ? WalkCoalesced(max_steps) : WalkWideNodes(max_steps);
      Grow(misses_, requests);
      const std::size_t m = l1_.AccessAll(request_sector_.data(), requests, misses_.data());
      const MissSlots out = AddMisses(m);
      for (std::size_t j = 0; j < m; ++j) {
        const std::uint32_t group = request_group_[misses_[j]];
        out.sector[j] = request_sector_[misses_[j]];
        out.owner[j] = group_owner_[group];
        out.group_end[j] = j + 1 == m || request_group_[misses_[j + 1]] != group;
      }
      out_.requests += requests;
    }
    out_.wave_end.push_back(static_cast<std::uint32_t>(out_.sector.size()));
  }

 private:
  // Buffers only grow: a shorter wave leaves the tail unused.
  template <class Vector>
  static void Grow(Vector& v, std::size_t n) {
    if (v.size() < n) v.resize(std::max(n, 2 * v.size()));
  }

  std::uint32_t Sector(std::uint64_t address) const {
    return static_cast<std::uint32_t>((address - begin_) >> sector_shift_);
  }

  // Fills owner_ and sector_ (one-sector nodes) or address_ with the wave's
  // fetches, step-major; step_start_[k] is where step k begins. Returns the
  // wave's step count.
  std::uint32_t SortByStep(const std::uint32_t* warps, std::size_t count) {
    const std::size_t n = record_.query_count();
    const std::uint64_t* offsets = record_.fetch_offsets.data();
    lane_addresses_.clear();
    lane_nodes_.clear();
    lane_owner_.clear();
    std::uint32_t max_steps = 0;
    for (std::size_t i = 0; i < count; ++i) {
      const std::size_t lo = static_cast<std::size_t>(warps[i]) * gpu_.warp_size;
      // A warp lies within one block, so its lanes' addresses follow one
      // another: the record's lookup once per warp, not per lane.
      const std::uint64_t* a = record_.addresses(lo);
      for (std::size_t q = lo; q < std::min(n, lo + gpu_.warp_size); ++q) {
        const auto nodes = static_cast<std::uint32_t>(offsets[q + 1] - offsets[q]);
        lane_addresses_.push_back(a);
        lane_nodes_.push_back(nodes);
        lane_owner_.push_back(coalesced_ ? warps[i] : static_cast<std::uint32_t>(q));
        a += nodes;
      }
      max_steps = std::max(max_steps, steps_[warps[i]]);
    }
    // Fetches per step = lanes with more nodes than the step's index.
    step_start_.assign(max_steps + 2, 0);
    for (std::uint32_t nodes : lane_nodes_) ++step_start_[nodes];
    std::uint32_t active = 0;
    for (std::uint32_t k = max_steps + 1; k-- > 0;) {
      const std::uint32_t ending_here = step_start_[k];
      step_start_[k] = active;  // lanes still active at step k
      active += ending_here;
    }
    std::uint32_t total = 0;
    for (std::uint32_t k = 0; k <= max_steps; ++k) {
      const std::uint32_t c = step_start_[k];
      step_start_[k] = total;
      total += c;
    }
    fetches_ = total;
    cursor_.assign(step_start_.begin(), step_start_.end());
    Grow(owner_, total);
    std::uint32_t* owner = owner_.data();
    if (one_sector_nodes_) {
      Grow(sector_, total);
      std::uint32_t* sector = sector_.data();
      const std::uint32_t* step_start = step_start_.data();
      const std::uint64_t begin = begin_;
      const int shift = sector_shift_;
      const bool coalesced = coalesced_;
      if (coalesced) {
        Scatter([&](std::uint32_t at, std::uint64_t address, std::uint32_t lane_owner, std::uint32_t k) {
          const auto s = static_cast<std::uint32_t>((address - begin) >> shift);
          // The previous lane of the same warp step fetched the same sector,
          // so this one adds no request; dropping it here (most neighbouring
          // rays share a sector) spares the walk. Without a branch (whether
          // neighbours share a sector is data, and mispredicted it cost more
          // than the stores): the slot is written either way, and a repeat
          // leaves it to the step's next fetch. It lies within step k's
          // range, since this fetch is one of the step's. At slot 0 the
          // comparison reads slot 0 and is masked off.
          const std::uint32_t previous = at - (at > 0);
          const bool repeat = (at > step_start[k]) & (sector[previous] == s) & (owner[previous] == lane_owner);
          sector[at] = s;
          owner[at] = lane_owner;
          return !repeat;
        });
      } else {
        Scatter([&](std::uint32_t at, std::uint64_t address, std::uint32_t lane_owner, std::uint32_t) {
          sector[at] = static_cast<std::uint32_t>((address - begin) >> shift);
          owner[at] = lane_owner;
          return true;
        });
      }
    } else {
      Grow(address_, total);
      std::uint64_t* address = address_.data();
      Scatter([&](std::uint32_t at, std::uint64_t a, std::uint32_t lane_owner, std::uint32_t) {
        address[at] = a;
        owner[at] = lane_owner;
        return true;
      });
    }
    return max_steps;
  }

  // Offers each fetch of the wave's lanes its step's next slot:
  // write(slot, address, owner, step) fills it, or declines (false) and
  // leaves the slot (which it may have written) to the next fetch of that
  // step. Afterwards step k's fetches are [step_start_[k], cursor_[k]).
  template <class Write>
  void Scatter(Write write) {
    std::uint32_t* cursor = cursor_.data();
    for (std::size_t j = 0; j < lane_nodes_.size(); ++j) {
      const std::uint32_t lane_owner = lane_owner_[j], nodes = lane_nodes_[j];
      const std::uint64_t* a = lane_addresses_[j];
      for (std::uint32_t k = 0; k < nodes; ++k) cursor[k] += write(cursor[k], a[k], lane_owner, k) ? 1 : 0;
    }
  }

  // Coalesced: one group per warp step (a warp's lanes are adjacent within
  // a step), each distinct sector of the step requested once. Fills the
  // request buffers; returns the request count.
  std::size_t WalkCoalesced(std::uint32_t max_steps) {
    const std::uint64_t span = one_sector_nodes_ ? 1 : SpanOf(record_.node_bytes);
    Grow(request_sector_, fetches_ * span);
    Grow(request_group_, fetches_ * span);
    group_owner_.clear();
    std::uint32_t* out_sector = request_sector_.data();
    std::uint32_t* out_group = request_group_.data();
    const std::uint32_t* owner = owner_.data();
    std::size_t r = 0, group_begin = 0;
    auto group = ~std::uint32_t{0};
    // Whether `s` is among the group's requests so far, and if not, notes
    // it. A sector claims its slot of `recent_` for its group when the slot
    // holds another group's; so a sector already requested in this group is
    // in its slot, unless another sector of the group held the slot first,
    // and only then are the group's requests scanned. The slot is a
    // multiplicative hash of the sector (a map's rows are often a multiple of
    // 64 sectors apart, which s mod 64 would send to one slot), in a table
    // large enough that a warp step's 32 sectors rarely share one.
    recent_.fill(~std::uint64_t{0});
    auto repeat = [&](std::uint32_t s) {
      std::uint64_t& slot = recent_[(s * 0x9E3779B1u) >> (32 - kRecentBits)];
      const std::uint64_t mine = std::uint64_t{group} << 32 | s;
      if (slot == mine) return true;
      if (slot >> 32 != group) {
        slot = mine;
        return false;
      }
      for (std::size_t i = r; i-- > group_begin;)
        if (out_sector[i] == s) return true;
      return false;
    };
    for (std::uint32_t k = 0; k < max_steps; ++k) {
      const std::uint32_t e0 = step_start_[k], e1 = cursor_[k];
      for (std::uint32_t e = e0; e < e1; ++e) {
        const bool starts = e == e0 || owner[e] != owner[e - 1];
        if (starts) {
          ++group;
          group_owner_.push_back(owner[e]);
          group_begin = r;
        }
        if (one_sector_nodes_) {
          const std::uint32_t s = sector_[e];
          if (repeat(s)) continue;
          out_sector[r] = s;
          out_group[r++] = group;
          continue;
        }
        const std::uint32_t last = Sector(address_[e] + record_.node_bytes - 1);
        for (std::uint32_t s = Sector(address_[e]); s <= last; ++s) {
          if (repeat(s)) continue;
          out_sector[r] = s;
          out_group[r++] = group;
        }
      }
    }
    return r;
  }

  // Per thread, nodes wider than a sector (or unaligned): one group per
  // fetch, every sector it spans.
  std::size_t WalkWideNodes(std::uint32_t max_steps) {
    const std::uint64_t span = SpanOf(record_.node_bytes);
    Grow(request_sector_, fetches_ * span);
    Grow(request_group_, fetches_ * span);
    group_owner_.clear();
    std::size_t r = 0;
    for (std::uint32_t e = 0; e < step_start_[max_steps]; ++e) {
      const auto group = static_cast<std::uint32_t>(group_owner_.size());
      group_owner_.push_back(owner_[e]);
      const std::uint32_t last = Sector(address_[e] + record_.node_bytes - 1);
      for (std::uint32_t s = Sector(address_[e]); s <= last; ++s) {
        request_sector_[r] = s;
        request_group_[r++] = group;
      }
    }
    return r;
  }

  // Sectors a node of `bytes` may span at any alignment.
  std::uint64_t SpanOf(std::uint64_t bytes) const { return (bytes + gpu_.sector_bytes - 1) / gpu_.sector_bytes + 1; }

  // Room for `count` more misses at the end of out_, to be written through
  // the pointers (push_back would store each vector's end at every miss).
  struct MissSlots {
    std::uint32_t* sector;
    std::uint32_t* owner;
    std::uint8_t* group_end;
  };
  MissSlots AddMisses(std::size_t count) {
    const std::size_t at = out_.sector.size();
    out_.sector.resize(at + count);
    out_.owner.resize(at + count);
    out_.group_end.resize(at + count);
    return {out_.sector.data() + at, out_.owner.data() + at, out_.group_end.data() + at};
  }

  std::vector<std::uint32_t> group_owner_;  // per group of the wave

  const KernelRecord& record_;
  const GpuParams& gpu_;
  const bool coalesced_;
  CacheLevel& l1_;
  const std::uint64_t begin_;
  const int sector_shift_;
  const std::vector<std::uint32_t>& steps_;
  SmMisses& out_;
  // Every node lies within one sector: a power-of-two size no larger than a
  // sector, at addresses aligned to it (the layouts guarantee it).
  bool one_sector_nodes_ = false;
  std::size_t fetches_ = 0;  // in the wave
  // Per lane of the wave: its query's first address, node count and owner.
  std::vector<const std::uint64_t*> lane_addresses_;
  std::vector<std::uint32_t> lane_nodes_, lane_owner_;
  std::vector<std::uint32_t> step_start_, cursor_;
  UninitializedVector<std::uint32_t> owner_, sector_, misses_, request_sector_, request_group_;
  UninitializedVector<std::uint64_t> address_;
  static constexpr int kRecentBits = 10;
  std::array<std::uint64_t, std::size_t{1} << kRecentBits> recent_;  // WalkCoalesced: (group, sector) per slot
};

// Per warp, whether the record's address sample kept it: KeepsWarp once
// per block (a block is kept or not as a whole), not its divisions per warp.
std::vector<std::uint8_t> KeptWarps(const AddressSample& sample, std::size_t warps) {
  std::vector<std::uint8_t> kept(warps, 1);
  const auto per_block = static_cast<std::size_t>(std::max(1, sample.warps_per_block));
  if (sample.KeepsAll()) return kept;
  for (std::size_t lo = 0; lo < warps; lo += per_block)
    if (!sample.KeepsWarp(lo))
      std::fill(kept.begin() + static_cast<long>(lo), kept.begin() + static_cast<long>(std::min(warps, lo + per_block)),
                0);
  return kept;
}

// The memory of the warps a sampled record did not keep, estimated from the
// kept ones. Each unkept warp borrows from a "twin", a kept warp at the
// same position in its SM's list of kept warps (the sampled SMs taken in
// turn by SM number): the warp at position k of its SM's list is paired
// with kept position k when every block is kept, and with the same warp of
// the nearest kept block before it otherwise. It borrows the twin's memory
// cycles beyond the L1 latency per unit of work (a warp step when
// coalesced; per thread, lane by lane, a node fetch), applied to its own
// unit count. Borrowing whole warps, rather than a mean, keeps the spread
// of memory latency over lanes and warps that a warp's slowest lane and an
// SM's busiest slot depend on. Sector requests per SM add the kept warps'
// mean per unit for the unkept units (a sum, which a mean estimates
// without bias). The totals scale by the ratio of all units to the kept
// units, except DRAM accesses when the L2 holds the footprint: those are
// exactly the sectors the whole batch touched, which the record counts.
// Exact in what needs no addresses (node counts, steps, exits),
// approximate in what the addresses decide; the error against exact
// replay is measured in tests/backends/sampled_pricing_test.cc.
void EstimateUnsampled(const KernelRecord& record, const GpuParams& gpu, const AccessPattern& pattern,
                       const std::vector<std::vector<std::uint32_t>>& sm_warps, const std::vector<std::uint8_t>& kept,
                       const std::vector<std::uint32_t>& steps, const std::vector<std::uint64_t>& units,
                       const std::vector<int>& replayed, std::uint64_t l1_latency, bool l2_holds_footprint,
                       MemoryProfile& profile) {
  const AddressSample& sample = record.address_sample;
  const std::size_t n = record.query_count();
  const std::size_t lanes = static_cast<std::size_t>(gpu.warp_size);
  const std::size_t per_block = static_cast<std::size_t>(gpu.warps_per_block);
  MemoryCycles& owner_cycles = pattern.coalesced ? profile.warp_memory_cycles : profile.query_memory_cycles;
  auto extra_of_query = [&](std::size_t q) { return owner_cycles[q] - l1_latency * record.nodes(q); };

  std::vector<std::uint64_t> unkept_units(gpu.sms, 0);
  std::uint64_t all_units = 0, kept_units = 0, kept_extra = 0, kept_requests = 0;
  std::vector<std::uint32_t> twins;  // the kept warps, interleaved SM by SM
  for (std::size_t j = 0;; ++j) {
    bool any = false;
    for (int sm : replayed) {
      // Position j of this SM's kept warps: block round j / per_block * stride.
      const std::size_t k = sample.RoundOfKept(j / per_block) * per_block + j % per_block;
      if (k < sm_warps[sm].size()) {
        twins.push_back(sm_warps[sm][k]);
        any = true;
      }
    }
    if (!any) break;
  }
  for (int sm : replayed) kept_requests += profile.sm_sector_requests[sm];
  for (int sm = 0; sm < gpu.sms; ++sm)
    for (std::uint32_t w : sm_warps[sm]) {
      all_units += units[w];
      if (!kept[w]) {
        unkept_units[sm] += units[w];
        continue;
      }
      kept_units += units[w];
      if (pattern.coalesced) {
        kept_extra += owner_cycles[w] - l1_latency * steps[w];
        continue;
      }
      for (std::size_t q = std::size_t{w} * lanes; q < std::min(n, (std::size_t{w} + 1) * lanes); ++q)
        kept_extra += extra_of_query(q);
    }
  // Per thread, an unkept query's cycles are written here whole (ReplayMemory
  // wrote only the kept ones): the L1 latency per node, then what it borrows.
  if (kept_units == 0 || all_units == kept_units || twins.empty()) {
    if (!pattern.coalesced)
      for (std::size_t w = 0; w < kept.size(); ++w)
        if (!kept[w]) WriteL1Cycles(record, w, lanes, l1_latency, owner_cycles.data());
    return;
  }
  const double mean_extra = static_cast<double>(kept_extra) / static_cast<double>(kept_units);
  const double requests_per_unit = static_cast<double>(kept_requests) / static_cast<double>(kept_units);
  // Cycles beyond the L1 per unit of `twin` (a warp, or a query), or the
  // kept mean when the twin did no work.
  auto rate = [&](std::uint64_t extra, std::uint64_t units) {
    return units > 0 ? static_cast<double>(extra) / static_cast<double>(units) : mean_extra;
  };
  // Each lane's rank in its warp by node count, ties in launch order: its
  // key (node count, lane) is distinct, so its rank is the number of smaller
  // keys (key_ranks.h; in 32 bits where node counts allow, which runs in
  // more SIMD lanes). Also gives the lanes' node counts.
  auto RanksByNodes = [&](std::uint32_t warp, std::vector<std::uint32_t>& rank, std::uint32_t* lane_nodes) {
    const std::size_t first = std::size_t{warp} * lanes, count = std::min(n, first + lanes) - first;
    std::uint32_t most = 0;
    for (std::size_t i = 0; i < count; ++i) {
      lane_nodes[i] = record.nodes(first + i);
      most = std::max(most, lane_nodes[i]);
    }
    rank.resize(count);
    auto rank_keys = [&](auto key_type) {
      using Key = decltype(key_type);
      Key key[kMaxRankedKeys], place[kMaxRankedKeys];
      for (std::size_t i = 0; i < count; ++i) key[i] = static_cast<Key>(std::uint64_t{lane_nodes[i]} << 6 | i);
      RankDistinctKeys(key, count, place);
      for (std::size_t i = 0; i < count; ++i) rank[i] = static_cast<std::uint32_t>(place[i]);
    };
    if (most < (std::uint32_t{1} << 25))  // (node count, lane) fits a signed 32-bit key
      rank_keys(std::int32_t{});
    else
      rank_keys(std::uint64_t{});
  };
  // The twin of the unkept warp at position k of SM sm's list: the same
  // warp of the nearest kept block round at or before its own, on a sampled
  // SM chosen by this SM's number.
  auto twin_of = [&](std::size_t sm, std::size_t k) {
    const std::size_t kept_position = sample.KeptRoundAtOrBefore(k / per_block) * per_block + k % per_block;
    return (kept_position * replayed.size() + sm % replayed.size()) % twins.size();
  };
  // Per thread, every twin's lanes' rates by rank of node count (a twin
  // lends to a warp of every unsampled SM), found before the SMs borrow
  // them: twin t's are rates[t * lanes, t * lanes + its lane count).
  std::vector<double> twin_rates(pattern.coalesced ? 0 : twins.size() * lanes);
  std::vector<std::uint32_t> twin_lanes(pattern.coalesced ? 0 : twins.size());
  if (!pattern.coalesced) {
    std::vector<std::uint32_t> twin_rank;
    std::uint32_t lane_nodes[kMaxRankedKeys];
    for (std::size_t t = 0; t < twins.size(); ++t) {
      RanksByNodes(twins[t], twin_rank, lane_nodes);
      double* theirs = twin_rates.data() + t * lanes;
      twin_lanes[t] = static_cast<std::uint32_t>(twin_rank.size());
      for (std::size_t i = 0; i < twin_rank.size(); ++i) {
        const std::size_t partner = std::size_t{twins[t]} * lanes + i;
        theirs[twin_rank[i]] = lane_nodes[i] > 0 ? rate(extra_of_query(partner), lane_nodes[i]) : mean_extra;
      }
    }
  }
  // SM by SM, each an OpenMP task (every SM writes only its own warps' cycles
  // and its own request count): a caller that replays several patterns at
  // once (PricingContext::ComputeExpected) lets an idle thread take SMs of
  // this estimate; anywhere else they run in turn on the calling thread.
  const auto sms = static_cast<std::size_t>(gpu.sms);
  LoopExceptions exceptions(sms);
#pragma omp taskloop grainsize(1) default(shared)
  for (std::size_t sm = 0; sm < sms; ++sm) {
    exceptions.Run(sm, [&] {
      profile.sm_sector_requests[sm] +=
          static_cast<std::uint64_t>(std::llround(requests_per_unit * static_cast<double>(unkept_units[sm])));
      std::vector<std::uint32_t> mine;
      std::uint32_t lane_nodes[kMaxRankedKeys];
      for (std::size_t k = 0; k < sm_warps[sm].size(); ++k) {
        const std::uint32_t w = sm_warps[sm][k];
        if (kept[w]) continue;
        const std::size_t t = twin_of(sm, k);
        const std::uint32_t twin = twins[t];
        if (pattern.coalesced) {
          AddRoundedCycles(owner_cycles[w],
                           rate(owner_cycles[twin] - l1_latency * steps[twin], steps[twin]) * steps[w]);
          continue;
        }
        // Per thread: lanes paired with the twin's by rank of node count (the
        // longest query with the twin's longest, ...), each borrowing its
        // partner's cycles per node. The pairing keeps the lanes' spread and
        // its tie to query length, which decide the warp's slowest lane.
        RanksByNodes(w, mine, lane_nodes);
        WriteBorrowedCycles(mine.data(), lane_nodes, mine.size(), twin_rates.data() + t * lanes, twin_lanes[t],
                            mean_extra, l1_latency, owner_cycles.data() + std::size_t{w} * lanes);
      }
    });
  }
  exceptions.RethrowFirst();
  const double scale = static_cast<double>(all_units) / static_cast<double>(kept_units);
  MemoryCounters& c = profile.totals;
  auto scaled = [&](std::uint64_t v) {
    return static_cast<std::uint64_t>(std::llround(static_cast<double>(v) * scale));
  };
  c.sector_requests = 0;
  for (std::uint64_t r : profile.sm_sector_requests) c.sector_requests += r;
  c.l2_accesses = std::min(scaled(c.l2_accesses), c.sector_requests);
  c.dram_accesses = l2_holds_footprint && record.touched_sectors > 0 ? record.touched_sectors : scaled(c.dram_accesses);
  c.dram_accesses = std::min(c.dram_accesses, c.l2_accesses);
  c.l2_hits = c.l2_accesses - c.dram_accesses;
  c.l1_hits = c.sector_requests - c.l2_accesses;
}

}  // namespace

MemoryCounters& MemoryCounters::operator+=(const MemoryCounters& more) {
  sector_requests += more.sector_requests;
  l1_hits += more.l1_hits;
  l2_accesses += more.l2_accesses;
  l2_hits += more.l2_hits;
  dram_accesses += more.dram_accesses;
  return *this;
}

int SmOfWarp(std::size_t warp, const GpuParams& gpu) {
  return static_cast<int>((warp / static_cast<std::size_t>(gpu.warps_per_block)) % static_cast<std::size_t>(gpu.sms));
}

// Block by block (block b on SM b mod sms), each SM's list sized first and
// a block's warps written as a run: no division per warp and no growth.
std::vector<std::vector<std::uint32_t>> WarpsBySm(std::size_t warps, const GpuParams& gpu) {
  const auto sms = static_cast<std::size_t>(gpu.sms);
  const auto per_block = static_cast<std::size_t>(gpu.warps_per_block);
  const std::size_t blocks = (warps + per_block - 1) / per_block;
  std::vector<std::vector<std::uint32_t>> sm_warps(sms);
  for (std::size_t sm = 0; sm < sms && sm < blocks; ++sm) {
    const std::size_t mine = (blocks - sm + sms - 1) / sms;  // blocks sm, sm + sms, ...
    const std::size_t last = sm + (mine - 1) * sms;          // its last block, perhaps partial
    std::vector<std::uint32_t>& list = sm_warps[sm];
    list.resize((mine - 1) * per_block + std::min(per_block, warps - last * per_block));
    std::uint32_t* at = list.data();
    for (std::size_t b = sm; b < blocks; b += sms) {
      const auto first = static_cast<std::uint32_t>(b * per_block);
      const auto count = static_cast<std::uint32_t>(std::min(warps, (b + 1) * per_block) - b * per_block);
      for (std::uint32_t i = 0; i < count; ++i) at[i] = first + i;
      at += count;
    }
  }
  return sm_warps;
}

std::size_t WarpCount(const KernelRecord& record, const GpuParams& gpu) {
  const std::size_t w = static_cast<std::size_t>(gpu.warp_size);
  return (record.query_count() + w - 1) / w;
}

// Two phases: (1) per SM, in parallel: replay its waves through its own L1
// (SmReplay), keeping only the misses; (2) serially: the misses of all SMs
// through the shared L2, wave round by wave round, SMs in order, charging
// each group with a miss when its last miss is served. Each SM's work is
// independent and the L2 order is fixed, so the result does not depend on
// the thread count. A sampled record replays its sampled SMs only, and
// EstimateUnsampled fills in the rest.
MemoryProfile ReplayMemory(const KernelRecord& record, const GpuParams& gpu, const AccessPattern& pattern) {
  return ReplayMemory(record, gpu, pattern,
                      CountWarpNodes(record.fetch_offsets, static_cast<std::size_t>(gpu.warp_size)));
}

MemoryProfile ReplayMemory(const KernelRecord& record, const GpuParams& gpu, const AccessPattern& pattern,
                           const WarpNodeCounts& warp_nodes) {
  const AddressSample& sample = record.address_sample;
  if (record.sampled() && !sample.SamePlacement(gpu.warp_size, gpu.warps_per_block, gpu.sms, gpu.sector_bytes))
    throw std::logic_error("ReplayMemory: the record's address sample was taken for another placement of warps on SMs");
  MemoryProfile profile;
  CacheHierarchy caches(gpu, record.footprint_begin(), std::max(record.footprint_end(), record.footprint_begin()));
  profile.l1_model = caches.l1_model();
  profile.l2_model = caches.l2_model();
  const std::uint64_t latency[3] = {static_cast<std::uint64_t>(caches.LatencyCycles(MemoryLevel::kL1)),
                                    static_cast<std::uint64_t>(caches.LatencyCycles(MemoryLevel::kL2)),
                                    static_cast<std::uint64_t>(caches.LatencyCycles(MemoryLevel::kDram))};

  // Groups: a warp has one per step (its slowest lane's node count); a
  // thread one per node fetch. Each waits for the L1 at least.
  const std::size_t n = record.query_count();
  const std::size_t warps = WarpCount(record, gpu);
  // Per warp, its units of work: steps when coalesced, its lanes' node
  // fetches per thread (what the sampled estimate scales by).
  const std::vector<std::vector<std::uint32_t>> sm_warps = WarpsBySm(warps, gpu);
  const std::vector<std::uint8_t> kept = KeptWarps(sample, warps);
  if (warp_nodes.steps.size() != warps || warp_nodes.lane_nodes.size() != warps)
    throw std::logic_error("ReplayMemory: the warp node counts are for another record or warp size");
  const std::vector<std::uint32_t>& steps = warp_nodes.steps;
  std::vector<std::uint64_t> warp_steps;
  if (pattern.coalesced) warp_steps.assign(steps.begin(), steps.end());
  const std::vector<std::uint64_t>& units = pattern.coalesced ? warp_steps : warp_nodes.lane_nodes;
  const std::uint64_t* offsets = record.fetch_offsets.data();
  MemoryCycles& owner_cycles = pattern.coalesced ? profile.warp_memory_cycles : profile.query_memory_cycles;
  // Through a pointer: push_back stored the vector's end at every entry.
  // Every entry is written below (or, for unkept queries, by
  // EstimateUnsampled): resize leaves them uninitialized (MemoryCycles).
  owner_cycles.resize(pattern.coalesced ? warps : n);
  std::uint64_t* first_cycles = owner_cycles.data();
  if (pattern.coalesced) {
    for (std::size_t w = 0; w < warps; ++w) first_cycles[w] = latency[0] * steps[w];
  } else if (!record.sampled()) {
    for (std::size_t q = 0; q < n; ++q) first_cycles[q] = latency[0] * (offsets[q + 1] - offsets[q]);
  } else {
    // The replayed (kept) warps' queries only: EstimateUnsampled writes the
    // others' whole, with their node counts at hand (a pass over every
    // query's offsets, out of the host's caches, showed in profiles).
    for (std::size_t w = 0; w < warps; ++w)
      if (kept[w]) WriteL1Cycles(record, w, static_cast<std::size_t>(gpu.warp_size), latency[0], first_cycles);
  }

  // The SMs replayed, each with the warps whose addresses the record kept
  // (all of its warps unless the sample skips blocks).
  const bool skips_blocks = record.sampled() && sample.Stride() > 1;
  std::vector<int> replayed;
  std::vector<std::vector<std::uint32_t>> kept_warps(gpu.sms);
  for (int sm = 0; sm < gpu.sms; ++sm) {
    if (record.sampled() && !sample.KeepsSm(sm)) continue;
    replayed.push_back(sm);
    if (!skips_blocks) continue;
    for (std::uint32_t w : sm_warps[sm])
      if (kept[w]) kept_warps[sm].push_back(w);
  }
  std::vector<SmMisses> sms(gpu.sms);
  const std::size_t wave = static_cast<std::size_t>(std::max(1, pattern.warps_per_wave));
  LoopExceptions exceptions(replayed.size());
#pragma omp parallel for schedule(dynamic, 1)
  for (int i = 0; i < static_cast<int>(replayed.size()); ++i) {
    exceptions.Run(static_cast<std::size_t>(i), [&] {
      const int sm = replayed[i];
      const std::vector<std::uint32_t>& list = skips_blocks ? kept_warps[sm] : sm_warps[sm];
      // Room for as many misses as the SM's warps fetch nodes (every miss,
      // when each node lies within one sector), so that the lists are not
      // copied as they grow.
      std::size_t fetches = 0;
      for (std::uint32_t w : list) fetches += warp_nodes.lane_nodes[w];
      sms[sm].Reserve(fetches);
      SmReplay replay(record, gpu, pattern, caches, sm, steps, sms[sm]);
      for (std::size_t lo = 0; lo < list.size(); lo += wave)
        replay.Wave(list.data() + lo, std::min(wave, list.size() - lo));
    });
  }
  exceptions.RethrowFirst();

  std::size_t rounds = 0;
  for (const SmMisses& s : sms) rounds = std::max(rounds, s.wave_end.size());
  std::vector<std::size_t> next_miss(gpu.sms, 0);
  CacheLevel& l2 = caches.L2();
  // A sampled record's L2 sees only the sampled SMs' misses, so a sector
  // the unsampled SMs would already have brought in misses to DRAM. When
  // the L2 holds the footprint, the batch misses exactly its touched
  // sectors, of which the sampled SMs' share is theirs by work; a group
  // whose slowest miss went to DRAM is then charged the L2 latency plus
  // that share of the DRAM latency (settled below, once the count of such
  // groups is known).
  const bool share_dram = record.sampled() && l2.cold() && record.touched_sectors > 0;
  // Per owner of the replayed warps, its groups whose slowest miss went to
  // DRAM, counted in an array over the replayed warps' owners only (an
  // array over every owner of the launch, zero-filled replay after replay,
  // showed in profiles): a warp's place among them (1 + its index, 0 if not
  // replayed), then its lane for a per-thread owner.
  std::vector<std::uint32_t> replayed_place, dram_groups;
  std::vector<std::uint32_t> dram_owners;  // those with a DRAM group, each once (the sampled SMs' few)
  const auto lanes = static_cast<std::size_t>(gpu.warp_size);
  if (share_dram) {
    replayed_place.assign(warps, 0);
    std::uint32_t places = 0;
    for (int sm : replayed)
      for (std::uint32_t w : skips_blocks ? kept_warps[sm] : sm_warps[sm]) replayed_place[w] = ++places;
    dram_groups.assign(pattern.coalesced ? places : std::size_t{places} * lanes, 0);
  }
  auto dram_groups_of = [&](std::uint32_t owner) -> std::uint32_t& {
    if (pattern.coalesced) return dram_groups[replayed_place[owner] - 1];
    return dram_groups[(replayed_place[owner / lanes] - 1) * lanes + owner % lanes];
  };
  for (std::size_t r = 0; r < rounds; ++r)
    for (int sm : replayed) {
      SmMisses& s = sms[sm];
      if (r >= s.wave_end.size()) continue;
      std::size_t& m = next_miss[sm];
      int slowest = 1;
      for (; m < s.wave_end[r]; ++m) {
        const int level = l2.Access(s.sector[m]) ? 1 : 2;
        ++(level == 1 ? s.l2_hits : s.dram);
        slowest = std::max(slowest, level);
        if (s.group_end[m]) {
          if (share_dram && slowest == 2) {
            if (dram_groups_of(s.owner[m])++ == 0) dram_owners.push_back(s.owner[m]);
            slowest = 1;
          }
          owner_cycles[s.owner[m]] += latency[slowest] - latency[0];
          slowest = 1;
        }
      }
    }
  if (share_dram) {
    std::uint64_t sampled_units = 0, all_units = 0, sampled_dram = 0;
    for (std::size_t w = 0; w < warps; ++w) {
      all_units += units[w];
      if (kept[w]) sampled_units += units[w];
    }
    for (int sm : replayed) sampled_dram += sms[sm].dram;
    const double expected = static_cast<double>(record.touched_sectors) * static_cast<double>(sampled_units) /
                            static_cast<double>(std::max<std::uint64_t>(1, all_units));
    const double p = sampled_dram > 0 ? std::min(1.0, expected / static_cast<double>(sampled_dram)) : 0.0;
    const double extra = p * static_cast<double>(latency[2] - latency[1]);
    for (std::uint32_t owner : dram_owners)
      owner_cycles[owner] += static_cast<std::uint64_t>(std::llround(extra * dram_groups_of(owner)));
  }

  profile.sm_sector_requests.assign(gpu.sms, 0);
  MemoryCounters& c = profile.totals;
  for (int sm : replayed) {
    const SmMisses& s = sms[sm];
    profile.sm_sector_requests[sm] = s.requests;
    c.sector_requests += s.requests;
    c.l1_hits += s.requests - s.sector.size();
    c.l2_accesses += s.sector.size();
    c.l2_hits += s.l2_hits;
    c.dram_accesses += s.dram;
  }
  if (record.sampled())
    EstimateUnsampled(record, gpu, pattern, sm_warps, kept, steps, units, replayed, latency[0], caches.L2().cold(),
                      profile);
  return profile;
}

ExitProfile ProfileExits(const KernelRecord& record) {
  if (record.tallied_exits) return *record.tallied_exits;
  const std::size_t n = record.query_count();
  const std::uint64_t* offsets = record.fetch_offsets.data();
  if (record.exits_per_query()) {
    // Every pass but the last has no exit: at most two variants per query,
    // in the order the general scan below gives them.
    ExitProfile profile;
    profile.offsets.assign(n + 1, 0);
    profile.variant.reserve(2 * n);
    profile.passes.reserve(2 * n);
    for (std::size_t q = 0; q < n; ++q) {
      const std::uint32_t quiet = record.QuietPasses(q);
      if (quiet > 0) {
        profile.variant.push_back(0);
        profile.passes.push_back(quiet);
      }
      if (record.LastPassExits(q)) {
        profile.variant.push_back(static_cast<std::uint8_t>(1 + record.last_exits[q]));
        profile.passes.push_back(1);
      }
      profile.offsets[q + 1] = profile.variant.size();
    }
    return profile;
  }
  const std::uint8_t* exits = record.node_exits.data();
  // One pass over the exits: each thread tallies a contiguous range of
  // queries into its own lists, which are then concatenated in query order
  // (the profile does not depend on the thread count).
  struct alignas(64) Part {  // a thread's own cache lines: its lists grow query by query
    std::vector<std::uint32_t> sizes;  // per query of the range
    std::vector<std::uint8_t> variant;
    std::vector<std::uint32_t> passes;
  };
  const int threads = std::max(1, omp_get_max_threads());
  std::vector<Part> parts(static_cast<std::size_t>(threads));
#pragma omp parallel num_threads(threads)
  {
    const auto t = static_cast<std::size_t>(omp_get_thread_num());
    const auto used = static_cast<std::size_t>(omp_get_num_threads());
    Part& part = parts[t];
    const std::size_t first = n * t / used, last = n * (t + 1) / used;
    part.sizes.reserve(last - first);
    part.variant.reserve(2 * (last - first));
    part.passes.reserve(2 * (last - first));
    ExitTally tally;
    for (std::size_t q = first; q < last; ++q) {
      for (std::uint64_t i = offsets[q]; i < offsets[q + 1]; ++i) tally.Add(exits[i]);
      part.sizes.push_back(tally.Append(part.variant, part.passes));
    }
  }
  ExitProfile profile;
  profile.offsets.assign(n + 1, 0);
  std::size_t q = 0;
  for (const Part& part : parts) {
    for (const std::uint32_t size : part.sizes) {
      profile.offsets[q + 1] = profile.offsets[q] + size;
      ++q;
    }
    profile.variant.insert(profile.variant.end(), part.variant.begin(), part.variant.end());
    profile.passes.insert(profile.passes.end(), part.passes.begin(), part.passes.end());
  }
  return profile;
}

}  // namespace rc
