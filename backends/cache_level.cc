#include "backends/cache_level.h"

#include <algorithm>

namespace rc {

CacheLevel::CacheLevel(std::uint64_t footprint_lines, int per_line_shift, std::uint64_t capacity_lines, int ways)
    : per_line_shift_(per_line_shift), sector_mask_((1u << per_line_shift) - 1) {
  if (Fits(footprint_lines, capacity_lines)) {
    mode_ = Mode::kCold;
    valid_.assign(((footprint_lines << per_line_shift) + 63) / 64, 0);
  } else if (ways == 0) {
    mode_ = Mode::kFullyAssociative;
    capacity_ = capacity_lines;
    mask_.assign(footprint_lines, 0);
    last_.assign(footprint_lines, 0);
    // Compacting costs O(history) and leaves at most `capacity` entries;
    // doing it when the history holds a few times that makes it O(1) per
    // access, and keeps the history small enough to stay in the host's
    // caches.
    history_.resize(std::max<std::size_t>(std::size_t{1} << 14, 4 * static_cast<std::size_t>(capacity_lines)));
  } else {
    mode_ = Mode::kSetAssociative;
    ways_ = static_cast<std::uint64_t>(ways);
    sets_ = capacity_lines / ways_;
    tags_.assign(sets_ * ways_, -1);
    set_masks_.assign(sets_ * ways_, 0);
    stamps_.assign(sets_ * ways_, 0);
  }
}

std::size_t CacheLevel::AccessAll(const std::uint32_t* sectors, std::size_t n, std::uint32_t* misses) {
  switch (mode_) {
    case Mode::kCold: return AccessCold(sectors, n, misses);
    case Mode::kFullyAssociative: return AccessFullyAssociative(sectors, n, misses);
    case Mode::kSetAssociative: break;
  }
  std::size_t m = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (!AccessSet(sectors[i] >> per_line_shift_, static_cast<std::uint8_t>(1u << (sectors[i] & sector_mask_))))
      misses[m++] = static_cast<std::uint32_t>(i);
  return m;
}

std::size_t CacheLevel::AccessCold(const std::uint32_t* sectors, std::size_t n, std::uint32_t* misses) {
  std::uint64_t* valid = valid_.data();
  std::size_t m = 0;
  std::uint32_t previous = ~std::uint32_t{0};
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t s = sectors[i];
    if (s == previous) continue;  // the sector just accessed: a hit
    previous = s;
    const std::uint64_t word = valid[s >> 6], bit = std::uint64_t{1} << (s & 63);
    if (word & bit) continue;
    valid[s >> 6] = word | bit;
    misses[m++] = static_cast<std::uint32_t>(i);
  }
  return m;
}

namespace {

// Keeps, of the history entries from `tail` on, each resident line's last
// access, in order and renumbered (which keeps the LRU order). Returns the
// new size; the tail becomes 0.
std::uint32_t CompactHistory(std::uint32_t* history, std::uint32_t size, std::uint32_t tail, const std::uint8_t* mask,
                             std::uint32_t* last) {
  std::uint32_t kept = 0;
  for (std::uint32_t t = tail; t < size; ++t) {
    const std::uint32_t line = history[t];
    if (mask[line] != 0 && last[line] == t) {
      history[kept] = line;
      last[line] = kept++;
    }
  }
  return kept;
}

}  // namespace

std::size_t CacheLevel::AccessFullyAssociative(const std::uint32_t* sectors, std::size_t n, std::uint32_t* misses) {
  std::uint8_t* mask = mask_.data();
  std::uint32_t* last = last_.data();
  std::uint32_t* history = history_.data();
  const auto history_capacity = static_cast<std::uint32_t>(history_.size());
  std::uint32_t size = history_size_, tail = tail_;
  std::uint64_t resident = resident_;
  const std::uint64_t capacity = capacity_;
  const int shift = per_line_shift_;
  const std::uint32_t sector_mask = sector_mask_;
  std::size_t m = 0;
  // Every access is appended to the history, a repeat of the most recently
  // used line too (its older entry dies), and a miss is written
  // unconditionally and counted by its flag: hits, misses and repeats
  // interleave unpredictably, and a mispredicted branch per access cost
  // more than the extra history entries.
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t sector = sectors[i];
    const std::uint32_t line = sector >> shift;
    const auto bit = static_cast<std::uint8_t>(1u << (sector & sector_mask));
    if (size == history_capacity) {
      size = CompactHistory(history, size, tail, mask, last);
      tail = 0;
    }
    last[line] = size;
    history[size++] = line;
    const std::uint8_t resident_sectors = mask[line];
    mask[line] = resident_sectors | bit;
    misses[m] = static_cast<std::uint32_t>(i);
    m += (resident_sectors & bit) == 0;
    if (resident_sectors == 0) {   // the line comes in
      if (resident == capacity) {  // evict the least recently used line (not this one: it is the newest)
        while (mask[history[tail]] == 0 || last[history[tail]] != tail) ++tail;
        mask[history[tail]] = 0;
        ++tail;
      } else {
        ++resident;
      }
    }
  }
  history_size_ = size;
  tail_ = tail;
  resident_ = resident;
  return m;
}

bool CacheLevel::AccessSet(std::uint32_t line, std::uint8_t bit) {
  const std::uint64_t base = (line % sets_) * ways_;
  ++clock_;
  std::uint64_t victim = base;
  for (std::uint64_t w = base; w < base + ways_; ++w) {
    if (tags_[w] == line) {
      const bool hit = set_masks_[w] & bit;
      set_masks_[w] |= bit;
      stamps_[w] = clock_;
      return hit;
    }
    if (stamps_[w] < stamps_[victim]) victim = w;  // empty ways have stamp 0
  }
  tags_[victim] = line;
  set_masks_[victim] = bit;
  stamps_[victim] = clock_;
  return false;
}

}  // namespace rc
