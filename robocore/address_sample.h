#pragma once
// Which queries of a batch a kernel record keeps the node addresses of.
//
// The cost models replay a batch's memory traffic SM by SM (each SM's L1
// sees only its own warps, in their order), so the unit of sampling is a
// block on a sampled SM: a sampled record keeps the addresses of every
// query of a kept block, and none of the others. A sampled SM keeps every
// block_stride-th of its blocks (its first, and so on), so its L1 sees
// whole blocks in their order. The memory replay
// (backends/memory_replay.h) replays the kept blocks exactly and estimates
// the others from them; every other part of the price (node counts, exits,
// warp divergence) stays exact because the record keeps those for every
// query.
//
// The placement is the GPU model's (warps of warp_size consecutive queries,
// blocks of warps_per_block warps dealt to `sms` SMs round-robin), so a
// sample is only meaningful for a GPU with the same three numbers; the
// replay refuses any other.
#include <cstddef>

#include "common/parameter_spec.h"

namespace rc {

// What the priced runs of rcbench keep (SchedulerCli's defaults): one SM of
// the GPU's, and every second block of it. Halving what is replayed halves
// the sampled SM's replay; the error it adds is measured against exact
// replay on DeliBot batches (tests/backends/sampled_pricing_test.cc,
// docs/pricing.md): one SM of eight, every RT unit's cycles within 3.5%;
// every second block of it, within 6%, and the demo's modelled total 1.0%
// above exact.
inline constexpr int kReplaySms = 1;
inline constexpr ParameterSpec kReplaySmsSpec{
    "SMs", 0, 1 << 16,
    "assumption: the SMs' warps are drawn alike; error measured in docs/pricing.md (\"Sampled SMs and blocks\")"};
inline constexpr int kReplayBlockStride = 2;
inline constexpr ParameterSpec kReplayBlockStrideSpec{"blocks", 1, 1 << 16,
                                                      "assumption: a sampled SM's blocks are drawn alike; error "
                                                      "measured in docs/pricing.md (\"Sampled SMs and blocks\")"};
static_assert(kReplaySmsSpec.min <= kReplaySms && kReplaySms <= kReplaySmsSpec.max &&
              kReplayBlockStrideSpec.min <= kReplayBlockStride && kReplayBlockStride <= kReplayBlockStrideSpec.max);

struct AddressSample {
  int warp_size = 32;       // threads
  int warps_per_block = 8;  // warps
  int sms = 8;              // count
  int sector_bytes = 32;    // bytes; what touched_sectors counts (a power of two)
  // SMs whose addresses are kept, spread evenly over the `sms`
  // (SM s is kept when (s * sampled_sms) mod sms < sampled_sms: SM 0 for
  // one, SMs 0 and sms/2 for two, ...); 0 or >= sms keeps every query.
  int sampled_sms = 0;
  // Of a sampled SM's blocks, in launch order, every block_stride-th is
  // kept (count, >= 1; 1 = all of them). Applies only when SMs are sampled
  // (0 < sampled_sms < sms): a record that keeps every SM keeps every block.
  int block_stride = 1;

  bool KeepsAll() const { return sampled_sms <= 0 || sampled_sms >= sms; }
  // Queries per block (warp_size x warps_per_block, at least 1): a sample
  // keeps a block's queries all or none.
  std::size_t BlockQueries() const {
    const std::size_t q = static_cast<std::size_t>(warp_size > 0 ? warp_size : 0) *
                          static_cast<std::size_t>(warps_per_block > 0 ? warps_per_block : 0);
    return q > 0 ? q : 1;
  }
  bool KeepsSm(int sm) const { return KeepsAll() || (sm * sampled_sms) % sms < sampled_sms; }
  std::size_t Stride() const { return static_cast<std::size_t>(block_stride < 1 ? 1 : block_stride); }
  // Whether block round `round` (a block's place in its SM's list) of a
  // sampled SM is kept.
  bool KeepsRound(std::size_t round) const { return round % Stride() == 0; }
  // Kept rounds are numbered 0, 1, ... in launch order: the number of the
  // last kept round at or before `round`, and the round of kept number `kept`.
  std::size_t KeptRoundAtOrBefore(std::size_t round) const { return round / Stride(); }
  std::size_t RoundOfKept(std::size_t kept) const { return kept * Stride(); }
  bool KeepsWarp(std::size_t warp) const {
    if (KeepsAll()) return true;
    const std::size_t block = warp / static_cast<std::size_t>(warps_per_block);
    const std::size_t round = block / static_cast<std::size_t>(sms);  // the block's place in its SM's list
    return KeepsSm(static_cast<int>(block % static_cast<std::size_t>(sms))) && KeepsRound(round);
  }
  bool KeepsQuery(std::size_t query) const {
    return KeepsAll() || KeepsWarp(query / static_cast<std::size_t>(warp_size));
  }
  bool SamePlacement(int warp_size_, int warps_per_block_, int sms_, int sector_bytes_) const {
    return warp_size == warp_size_ && warps_per_block == warps_per_block_ && sms == sms_ &&
           sector_bytes == sector_bytes_;
  }
};

}  // namespace rc
