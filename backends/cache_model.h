#pragma once
// The GPU's data caches: one L1 per SM and a shared L2 (paper: L1 64 KB
// fully associative LRU, 20 cycles; L2 3 MB 16-way LRU, 160 cycles), with
// 128-byte lines filled one 32-byte sector at a time (artifact: sectored
// caches).
//
// The model is as detailed as the working set demands (DESIGN.md). The
// kernel's footprint (every region it may fetch from, contiguous by
// construction, robocore/kernel_record.h) decides per level:
//   footprint <= capacity  "cold": a bit per sector; the first access to a
//                          sector misses, every later one hits. Exact for an
//                          LRU cache that holds the whole footprint, because
//                          such a cache never evicts.
//   footprint >  capacity  "lru": the L1 as a fully associative LRU list of
//                          lines (O(1) per access); the L2 as 16-way sets of
//                          lines indexed by line number modulo the set count.
//                          (cache_level.h: one level, its data structures.)
// Examples with the defaults: a 400 x 300 grid of 1-byte cells is 117 KiB,
// which does NOT fit the 64 KiB L1 (it takes the LRU path there) but fits
// the L2; the Wean map's 800 x 800 grid (625 KiB) and its 4-byte distance
// field (2.4 MiB) fit the L2 but not the L1; a 256 x 256 grid (64 KiB) fits
// the L1.
//
// Left out, and why it is safe here: writes (the kernels only read the
// scene), MSHR merging (a second request to a sector in flight is counted
// as a hit, which is what merging achieves for latency), L2 banking and
// interconnect queueing (bandwidth enters the backends as first-order
// bounds), and the artifact's hashed L2 set index (with a contiguous
// footprint, modulo indexing spreads lines evenly).
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "backends/cache_level.h"
#include "backends/gpu_params.h"

namespace rc {

enum class MemoryLevel : std::uint8_t { kL1 = 0, kL2 = 1, kDram = 2 };

class CacheHierarchy {
 public:
  // [footprint_begin, footprint_end): every byte the kernel may read.
  CacheHierarchy(const GpuParams& gpu, std::uint64_t footprint_begin, std::uint64_t footprint_end);

  // One 32-byte sector request from SM `sm`: where it was served from.
  MemoryLevel Access(int sm, std::uint64_t address);

  // The levels themselves, for a replay that runs each SM's L1 on its own
  // (in parallel; each SM's L1 may be driven from its own thread) and then
  // the shared L2 on the L1 misses in a fixed order. Sectors are numbered
  // from the footprint's first line. An SM's L1 is made when first asked
  // for, so a replay of a few sampled SMs sizes no state for the others;
  // different SMs' L1s may be asked for from different threads at once,
  // one SM's from one thread at a time.
  std::uint32_t SectorNumber(std::uint64_t address) const {
    return static_cast<std::uint32_t>((address - begin_) >> sector_shift_);
  }
  std::uint64_t begin() const { return begin_; }
  int sector_shift() const { return sector_shift_; }
  CacheLevel& L1(int sm);
  CacheLevel& L2() { return l2_.front(); }

  // Core cycles from request to data: L1 hit; L1 miss + L2 hit; + DRAM.
  // They grow level by level (GpuParams::IsValid: extra latencies >= 0).
  int LatencyCycles(MemoryLevel level) const { return latency_[static_cast<int>(level)]; }

  const std::string& l1_model() const { return l1_model_; }
  const std::string& l2_model() const { return l2_model_; }

 private:
  std::uint64_t begin_;
  int sector_shift_;  // log2(sector_bytes): sizes are powers of two (GpuParams::IsValid)
  int line_shift_;
  int latency_[3];
  std::uint64_t lines_;  // in the footprint
  int per_line_shift_;
  std::uint64_t l1_lines_;                       // an L1's capacity
  std::vector<std::unique_ptr<CacheLevel>> l1_;  // one per SM, made on first use
  std::vector<CacheLevel> l2_;                   // one
  std::string l1_model_;
  std::string l2_model_;
};

}  // namespace rc
