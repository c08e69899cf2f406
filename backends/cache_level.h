#pragma once
// One level of the data caches (cache_model.h): sectors in, hit or miss
// out. The replay calls Access once per sector request, billions of times
// in a sweep, so the two common paths (cold, fully associative LRU) are
// inline here; everything else is in cache_level.cc.
//
// Sectors are numbered from the footprint's first line: sector s lies in
// line s >> per_line_shift.
//
// Modes, chosen by the footprint (cache_model.h says why each is exact):
//   cold                 a valid bit per sector; the first access misses.
//   fully associative    LRU by timestamps: a line is resident while its
//                        sector mask is non-zero; history_ holds the line of
//                        every access that changed the LRU order, so the
//                        least recently used resident line is the first
//                        history entry that is still its line's last access.
//                        A hit on the most recently used line changes no
//                        order and is not recorded. O(1) amortized, two
//                        per-line words touched, no list relinking.
//   set associative      sets x ways of lines with a sector mask and a
//                        timestamp; the oldest way is evicted.
#include <cstdint>
#include <vector>

namespace rc {

class CacheLevel {
 public:
  // ways == 0: fully associative.
  CacheLevel(std::uint64_t footprint_lines, int per_line_shift, std::uint64_t capacity_lines, int ways);

  bool cold() const { return mode_ == Mode::kCold; }

  // True on a hit; on a miss the sector is filled (its line allocated,
  // evicting the least recently used line if the level is full).
  bool Access(std::uint32_t sector) {
    if (mode_ == Mode::kCold) {
      std::uint64_t& word = valid_[sector >> 6];
      const std::uint64_t bit = std::uint64_t{1} << (sector & 63);
      const bool hit = word & bit;
      word |= bit;
      return hit;
    }
    const std::uint32_t line = sector >> per_line_shift_;
    const auto bit = static_cast<std::uint8_t>(1u << (sector & sector_mask_));
    if (mode_ == Mode::kFullyAssociative) return AccessFullyAssociative(line, bit);
    return AccessSet(line, bit);
  }

 private:
  enum class Mode { kCold, kFullyAssociative, kSetAssociative };

  bool AccessFullyAssociative(std::uint32_t line, std::uint8_t bit) {
    std::uint8_t& mask = mask_[line];
    if (line != mru_) {
      if (history_.size() >= compact_at_) CompactHistory();
      last_[line] = static_cast<std::uint32_t>(history_.size());
      history_.push_back(line);
      mru_ = line;
      if (mask == 0) {
        if (resident_ == capacity_) EvictLeastRecentlyUsed();
        mask = bit;
        ++resident_;
        return false;
      }
    }
    const bool hit = mask & bit;
    mask |= bit;
    return hit;
  }
  void EvictLeastRecentlyUsed();
  void CompactHistory();
  bool AccessSet(std::uint32_t line, std::uint8_t bit);

  Mode mode_ = Mode::kCold;
  int per_line_shift_;
  std::uint32_t sector_mask_;
  // cold
  std::vector<std::uint64_t> valid_;
  // fully associative
  std::uint64_t capacity_ = 0, resident_ = 0;
  std::uint32_t tail_ = 0;
  std::uint32_t mru_ = ~std::uint32_t{0};  // the line of the last history entry
  std::size_t compact_at_ = 0;
  std::vector<std::uint8_t> mask_;      // per line: its resident sectors, 0 if absent
  std::vector<std::uint32_t> last_;     // per line: index of its last history entry
  std::vector<std::uint32_t> history_;  // the line of every recorded access, in order
  // set associative
  std::uint64_t ways_ = 0, sets_ = 0, clock_ = 0;
  std::vector<std::int64_t> tags_;
  std::vector<std::uint8_t> set_masks_;
  std::vector<std::uint64_t> stamps_;
};

}  // namespace rc
