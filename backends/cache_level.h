#pragma once
// One level of the data caches (cache_model.h): sectors in, hit or miss
// out. The replay drives a level with a whole wave of requests at a time
// (AccessAll), so each mode's loop keeps its state in registers.
//
// Sectors are numbered from the footprint's first line: sector s lies in
// line s >> per_line_shift.
//
// Modes, chosen by the footprint (cache_model.h says why each is exact):
//   cold                 a valid bit per sector; the first access misses.
//   fully associative    LRU by timestamps: a line is resident while its
//                        sector mask is non-zero; the history holds the line
//                        of every access, so the least recently used
//                        resident line is the first history entry that is
//                        still its line's last access. O(1) amortized, two
//                        per-line words touched, no list relinking, no
//                        branch on hit or miss but the line's arrival.
//   set associative      sets x ways of lines with a sector mask and a
//                        timestamp; the oldest way is evicted.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace rc {

class CacheLevel {
 public:
  // ways == 0: fully associative.
  CacheLevel(std::uint64_t footprint_lines, int per_line_shift, std::uint64_t capacity_lines, int ways);

  bool cold() const { return mode_ == Mode::kCold; }
  // Whether a level of `capacity_lines` holds a footprint of
  // `footprint_lines` (and is then cold: compulsory misses only).
  static bool Fits(std::uint64_t footprint_lines, std::uint64_t capacity_lines) {
    return footprint_lines <= capacity_lines;
  }

  // Accesses n sectors in order; a miss fills its sector (allocating its
  // line, evicting the least recently used line if the level is full).
  // Writes the index of every miss to `misses` (room for n) and returns
  // how many there were.
  std::size_t AccessAll(const std::uint32_t* sectors, std::size_t n, std::uint32_t* misses);
  // One sector: true on a hit.
  bool Access(std::uint32_t sector) {
    std::uint32_t miss;
    return AccessAll(&sector, 1, &miss) == 0;
  }

 private:
  enum class Mode { kCold, kFullyAssociative, kSetAssociative };

  std::size_t AccessCold(const std::uint32_t* sectors, std::size_t n, std::uint32_t* misses);
  std::size_t AccessFullyAssociative(const std::uint32_t* sectors, std::size_t n, std::uint32_t* misses);
  bool AccessSet(std::uint32_t line, std::uint8_t bit);

  Mode mode_ = Mode::kCold;
  int per_line_shift_;
  std::uint32_t sector_mask_;
  // cold
  std::vector<std::uint64_t> valid_;
  // fully associative
  std::uint64_t capacity_ = 0, resident_ = 0;
  std::uint32_t tail_ = 0;  // history entries before it are dead
  std::uint32_t history_size_ = 0;
  std::vector<std::uint8_t> mask_;      // per line: its resident sectors, 0 if absent
  std::vector<std::uint32_t> last_;     // per line: index of its last history entry
  std::vector<std::uint32_t> history_;  // fixed size: compacted when full
  // set associative
  std::uint64_t ways_ = 0, sets_ = 0, clock_ = 0;
  std::vector<std::int64_t> tags_;
  std::vector<std::uint8_t> set_masks_;
  std::vector<std::uint64_t> stamps_;
};

}  // namespace rc
