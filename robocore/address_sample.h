#pragma once
// Which queries of a batch a kernel record keeps the node addresses of.
//
// The cost models replay a batch's memory traffic SM by SM (each SM's L1
// sees only its own warps, in their order), so the unit of sampling is a
// whole SM: a sampled record keeps the addresses of every query whose warp
// runs on a sampled SM, and none of the others. The memory replay
// (backends/memory_replay.h) replays the sampled SMs exactly and estimates
// the others from them; every other part of the price (node counts, exits,
// warp divergence) stays exact because the record keeps those for every
// query.
//
// The placement is the GPU model's (warps of warp_size consecutive queries,
// blocks of warps_per_block warps dealt to `sms` SMs round-robin), so a
// sample is only meaningful for a GPU with the same three numbers; the
// replay refuses any other.
#include <cstddef>

namespace rc {

struct AddressSample {
  int warp_size = 32;       // threads
  int warps_per_block = 8;  // warps
  int sms = 8;              // count
  int sector_bytes = 32;    // bytes; what touched_sectors counts (a power of two)
  // SMs whose addresses are kept, spread evenly over the `sms`
  // (SM s is kept when (s * sampled_sms) mod sms < sampled_sms: SM 0 for
  // one, SMs 0 and sms/2 for two, ...); 0 or >= sms keeps every query.
  int sampled_sms = 0;

  bool KeepsAll() const { return sampled_sms <= 0 || sampled_sms >= sms; }
  bool KeepsSm(int sm) const { return KeepsAll() || (sm * sampled_sms) % sms < sampled_sms; }
  int SmOfQuery(std::size_t query) const {
    const std::size_t warp = query / static_cast<std::size_t>(warp_size);
    return static_cast<int>((warp / static_cast<std::size_t>(warps_per_block)) % static_cast<std::size_t>(sms));
  }
  bool KeepsQuery(std::size_t query) const { return KeepsAll() || KeepsSm(SmOfQuery(query)); }
  bool SamePlacement(int warp_size_, int warps_per_block_, int sms_, int sector_bytes_) const {
    return warp_size == warp_size_ && warps_per_block == warps_per_block_ && sms == sms_ &&
           sector_bytes == sector_bytes_;
  }
};

}  // namespace rc
