#include "backends/cache_level.h"

#include <algorithm>

namespace rc {

CacheLevel::CacheLevel(std::uint64_t footprint_lines, int per_line_shift, std::uint64_t capacity_lines,
                       int ways)
    : per_line_shift_(per_line_shift), sector_mask_((1u << per_line_shift) - 1) {
  if (footprint_lines <= capacity_lines) {
    mode_ = Mode::kCold;
    valid_.assign(((footprint_lines << per_line_shift) + 63) / 64, 0);
  } else if (ways == 0) {
    mode_ = Mode::kFullyAssociative;
    capacity_ = capacity_lines;
    mask_.assign(footprint_lines, 0);
    last_.assign(footprint_lines, 0);
    // Compacting costs O(history); doing it when the history is a few times
    // the capacity makes it O(1) per access, and keeps the history small
    // enough to stay in the host's caches.
    compact_at_ = std::max<std::size_t>(std::size_t{1} << 14, 4 * static_cast<std::size_t>(capacity_lines));
    history_.reserve(compact_at_);
  } else {
    mode_ = Mode::kSetAssociative;
    ways_ = static_cast<std::uint64_t>(ways);
    sets_ = capacity_lines / ways_;
    tags_.assign(sets_ * ways_, -1);
    set_masks_.assign(sets_ * ways_, 0);
    stamps_.assign(sets_ * ways_, 0);
  }
}

void CacheLevel::EvictLeastRecentlyUsed() {
  while (mask_[history_[tail_]] == 0 || last_[history_[tail_]] != tail_) ++tail_;
  mask_[history_[tail_]] = 0;
  ++tail_;
  --resident_;
}

// Only the entries from tail_ on matter, and of those only each resident
// line's last access. Keeping those, in order and renumbered, keeps the LRU
// order.
void CacheLevel::CompactHistory() {
  std::uint32_t kept = 0;
  for (std::uint32_t t = tail_; t < history_.size(); ++t) {
    const std::uint32_t line = history_[t];
    if (mask_[line] != 0 && last_[line] == t) {
      history_[kept] = line;
      last_[line] = kept++;
    }
  }
  history_.resize(kept);
  tail_ = 0;
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
