#include "backends/cache_model.h"

#include <stdexcept>

namespace rc {

// One cache level: "cold" (the footprint fits: a valid bit per sector) or
// "lru" (sets x ways of lines with a sector mask, least recently used
// evicted; a single set is kept as an O(1) doubly linked list).
class CacheHierarchy::Level {
 public:
  Level(std::uint64_t footprint_lines, int sectors_per_line, std::uint64_t capacity_lines,
        int ways)
      : sectors_per_line_(sectors_per_line) {
    if (footprint_lines <= capacity_lines) {
      mode_ = Mode::kCold;
      valid_.assign((footprint_lines * sectors_per_line + 63) / 64, 0);
    } else if (ways == 0) {  // fully associative
      mode_ = Mode::kFullyAssociative;
      capacity_ = capacity_lines;
      mask_.assign(footprint_lines, 0);
      prev_.assign(footprint_lines, -1);
      next_.assign(footprint_lines, -1);
    } else {
      mode_ = Mode::kSetAssociative;
      ways_ = ways;
      sets_ = capacity_lines / static_cast<std::uint64_t>(ways);
      tags_.assign(sets_ * ways_, -1);
      set_masks_.assign(sets_ * ways_, 0);
      stamps_.assign(sets_ * ways_, 0);
    }
  }

  bool cold() const { return mode_ == Mode::kCold; }

  // True on a hit; on a miss the sector is filled (its line allocated).
  bool Access(std::uint64_t line, int sector) {
    switch (mode_) {
      case Mode::kCold: {
        const std::uint64_t bit = line * sectors_per_line_ + sector;
        std::uint64_t& word = valid_[bit >> 6];
        const std::uint64_t m = std::uint64_t{1} << (bit & 63);
        const bool hit = word & m;
        word |= m;
        return hit;
      }
      case Mode::kFullyAssociative: return AccessList(static_cast<std::int64_t>(line), sector);
      case Mode::kSetAssociative: return AccessSet(static_cast<std::int64_t>(line), sector);
    }
    return false;
  }

 private:
  enum class Mode { kCold, kFullyAssociative, kSetAssociative };

  bool AccessList(std::int64_t line, int sector) {
    const std::uint8_t bit = static_cast<std::uint8_t>(1u << sector);
    if (mask_[line] != 0) {  // resident: move to the front
      const bool hit = mask_[line] & bit;
      mask_[line] |= bit;
      if (head_ != line) {
        Unlink(line);
        PushFront(line);
      }
      return hit;
    }
    if (resident_ == capacity_) {  // evict the least recently used line
      const std::int64_t victim = tail_;
      Unlink(victim);
      mask_[victim] = 0;
      --resident_;
    }
    mask_[line] = bit;
    PushFront(line);
    ++resident_;
    return false;
  }

  void Unlink(std::int64_t line) {
    const std::int64_t p = prev_[line], n = next_[line];
    if (p >= 0) next_[p] = n; else head_ = n;
    if (n >= 0) prev_[n] = p; else tail_ = p;
  }

  void PushFront(std::int64_t line) {
    prev_[line] = -1;
    next_[line] = head_;
    if (head_ >= 0) prev_[head_] = line;
    head_ = line;
    if (tail_ < 0) tail_ = line;
  }

  bool AccessSet(std::int64_t line, int sector) {
    const std::uint8_t bit = static_cast<std::uint8_t>(1u << sector);
    const std::uint64_t base = (static_cast<std::uint64_t>(line) % sets_) * ways_;
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

  Mode mode_ = Mode::kCold;
  int sectors_per_line_;
  // cold
  std::vector<std::uint64_t> valid_;
  // fully associative
  std::uint64_t capacity_ = 0, resident_ = 0;
  std::int64_t head_ = -1, tail_ = -1;
  std::vector<std::uint8_t> mask_;
  std::vector<std::int64_t> prev_, next_;
  // set associative
  std::uint64_t ways_ = 0, sets_ = 0, clock_ = 0;
  std::vector<std::int64_t> tags_;
  std::vector<std::uint8_t> set_masks_;
  std::vector<std::uint64_t> stamps_;
};

CacheHierarchy::CacheHierarchy(const GpuParams& gpu, std::uint64_t footprint_begin,
                               std::uint64_t footprint_end)
    : begin_(footprint_begin), sector_bytes_(gpu.sector_bytes), line_bytes_(gpu.line_bytes) {
  if (footprint_end < footprint_begin) throw std::invalid_argument("CacheHierarchy: empty footprint");
  // Lines are numbered from the footprint's first line, so every structure
  // is sized by the footprint, not by the address space.
  begin_ = footprint_begin / line_bytes_ * line_bytes_;
  const std::uint64_t lines = (footprint_end - begin_ + line_bytes_ - 1) / line_bytes_;
  const int sectors_per_line = line_bytes_ / sector_bytes_;
  for (int s = 0; s < gpu.sms; ++s)
    l1_.push_back(std::make_unique<Level>(lines, sectors_per_line,
                                          static_cast<std::uint64_t>(gpu.l1_bytes / line_bytes_), 0));
  l2_ = std::make_unique<Level>(lines, sectors_per_line,
                                static_cast<std::uint64_t>(gpu.l2_bytes / line_bytes_), gpu.l2_ways);
  const char* kFits = "cold (footprint fits: compulsory misses only)";
  l1_model_ = l1_.front()->cold() ? kFits : "lru (fully associative)";
  l2_model_ = l2_->cold() ? kFits : "lru (set associative)";
  latency_[0] = gpu.l1_latency_cycles;
  latency_[1] = latency_[0] + gpu.l2_latency_cycles;
  latency_[2] = latency_[1] + gpu.DramExtraCycles();
}

CacheHierarchy::~CacheHierarchy() = default;

MemoryLevel CacheHierarchy::Access(int sm, std::uint64_t address) {
  const std::uint64_t offset = address - begin_;
  const std::uint64_t line = offset / line_bytes_;
  const int sector = static_cast<int>(offset % line_bytes_) / sector_bytes_;
  if (l1_[sm]->Access(line, sector)) return MemoryLevel::kL1;
  if (l2_->Access(line, sector)) return MemoryLevel::kL2;
  return MemoryLevel::kDram;
}

}  // namespace rc
