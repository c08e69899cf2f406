#include "backends/cache_model.h"

#include <stdexcept>

namespace rc {
namespace {

int Log2(int power_of_two) {
  int shift = 0;
  while ((1 << shift) < power_of_two) ++shift;
  if ((1 << shift) != power_of_two) throw std::invalid_argument("cache sizes must be powers of two");
  return shift;
}

}  // namespace

// One cache level: "cold" (the footprint fits: a valid bit per sector) or
// "lru" (sets x ways of lines with a sector mask, the least recently used
// line evicted; a single set, the fully associative L1, by timestamps).
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
      last_.assign(footprint_lines, 0);
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

  // A whole stream at once (the replay's L1 phase): level[i] = 0 on a hit,
  // 1 on a miss, and misses lists the missing indices. Same results as
  // calling Access in order; the fully associative case keeps its state in
  // registers for the loop.
  void AccessStream(const std::uint32_t* sectors, std::size_t n, int per_line_shift,
                    std::uint8_t* level, std::vector<std::uint32_t>& misses) {
    const std::uint32_t sector_mask = (1u << per_line_shift) - 1;
    if (mode_ != Mode::kFullyAssociative) {
      for (std::size_t i = 0; i < n; ++i) {
        const bool hit = Access(sectors[i] >> per_line_shift, static_cast<int>(sectors[i] & sector_mask));
        level[i] = hit ? 0 : 1;
        if (!hit) misses.push_back(static_cast<std::uint32_t>(i));
      }
      return;
    }
    if (history_.size() + n >= (std::uint64_t{1} << 32))
      throw std::length_error("cache model: more than 2^32 accesses to one L1");
    const std::size_t first = history_.size();
    history_.resize(first + n);
    std::uint32_t* history = history_.data();
    std::uint8_t* mask = mask_.data();
    std::uint32_t* last = last_.data();
    std::uint32_t tail = tail_;
    std::uint64_t resident = resident_;
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint32_t line = sectors[i] >> per_line_shift;
      const auto bit = static_cast<std::uint8_t>(1u << (sectors[i] & sector_mask));
      const auto now = static_cast<std::uint32_t>(first + i);
      history[now] = line;
      last[line] = now;
      if (mask[line] != 0) {
        const bool hit = mask[line] & bit;
        mask[line] |= bit;
        level[i] = hit ? 0 : 1;
        if (!hit) misses.push_back(static_cast<std::uint32_t>(i));
        continue;
      }
      if (resident == capacity_) {  // evict the least recently used line
        while (mask[history[tail]] == 0 || last[history[tail]] != tail) ++tail;
        mask[history[tail]] = 0;
        ++tail;
        --resident;
      }
      mask[line] = bit;
      ++resident;
      level[i] = 1;
      misses.push_back(static_cast<std::uint32_t>(i));
    }
    tail_ = tail;
    resident_ = resident;
  }

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
      case Mode::kFullyAssociative: return AccessList(static_cast<std::uint32_t>(line), sector);
      case Mode::kSetAssociative: return AccessSet(static_cast<std::int64_t>(line), sector);
    }
    return false;
  }

 private:
  enum class Mode { kCold, kFullyAssociative, kSetAssociative };

  // Fully associative LRU by timestamps: a line is resident while its mask
  // is non-zero; history_ names the line of every access in order, so the
  // least recently used resident line is the first history entry that is
  // still its line's last access. Each entry is passed over at most once, so
  // an access costs O(1) amortized and touches two per-line words, instead
  // of relinking a list.
  bool AccessList(std::uint32_t line, int sector) {
    const std::uint8_t bit = static_cast<std::uint8_t>(1u << sector);
    const std::uint32_t now = static_cast<std::uint32_t>(history_.size());
    history_.push_back(line);
    if (mask_[line] != 0) {
      const bool hit = mask_[line] & bit;
      mask_[line] |= bit;
      last_[line] = now;
      return hit;
    }
    if (resident_ == capacity_) {  // evict the least recently used line
      while (mask_[history_[tail_]] == 0 || last_[history_[tail_]] != tail_) ++tail_;
      mask_[history_[tail_]] = 0;
      ++tail_;
      --resident_;
    }
    mask_[line] = bit;
    last_[line] = now;
    ++resident_;
    return false;
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
  std::uint32_t tail_ = 0;
  std::vector<std::uint8_t> mask_;
  std::vector<std::uint32_t> last_;     // per line: time of its last access
  std::vector<std::uint32_t> history_;  // per access: its line
  // set associative
  std::uint64_t ways_ = 0, sets_ = 0, clock_ = 0;
  std::vector<std::int64_t> tags_;
  std::vector<std::uint8_t> set_masks_;
  std::vector<std::uint64_t> stamps_;
};

CacheHierarchy::CacheHierarchy(const GpuParams& gpu, std::uint64_t footprint_begin,
                               std::uint64_t footprint_end)
    : begin_(footprint_begin), sector_shift_(Log2(gpu.sector_bytes)), line_shift_(Log2(gpu.line_bytes)) {
  if (footprint_end < footprint_begin) throw std::invalid_argument("CacheHierarchy: empty footprint");
  if (((footprint_end - footprint_begin) >> sector_shift_) >= (std::uint64_t{1} << 31))
    throw std::invalid_argument("CacheHierarchy: footprint beyond 2^31 sectors");
  // Lines are numbered from the footprint's first line, so every structure
  // is sized by the footprint, not by the address space.
  begin_ = footprint_begin >> line_shift_ << line_shift_;
  const std::uint64_t line_bytes = std::uint64_t{1} << line_shift_;
  const std::uint64_t lines = (footprint_end - begin_ + line_bytes - 1) >> line_shift_;
  const int sectors_per_line = 1 << (line_shift_ - sector_shift_);
  for (int s = 0; s < gpu.sms; ++s)
    l1_.push_back(std::make_unique<Level>(lines, sectors_per_line,
                                          static_cast<std::uint64_t>(gpu.l1_bytes) >> line_shift_, 0));
  l2_ = std::make_unique<Level>(lines, sectors_per_line,
                                static_cast<std::uint64_t>(gpu.l2_bytes) >> line_shift_, gpu.l2_ways);
  const char* kFits = "cold (footprint fits: compulsory misses only)";
  l1_model_ = l1_.front()->cold() ? kFits : "lru (fully associative)";
  l2_model_ = l2_->cold() ? kFits : "lru (set associative)";
  latency_[0] = gpu.l1_latency_cycles;
  latency_[1] = latency_[0] + gpu.l2_latency_cycles;
  latency_[2] = latency_[1] + gpu.DramExtraCycles();
}

CacheHierarchy::~CacheHierarchy() = default;

void CacheHierarchy::AccessL1(int sm, const std::uint32_t* sectors, std::size_t n, std::uint8_t* level,
                              std::vector<std::uint32_t>& misses) {
  l1_[sm]->AccessStream(sectors, n, line_shift_ - sector_shift_, level, misses);
}

bool CacheHierarchy::AccessL2(std::uint32_t sector) {
  const int per_line_shift = line_shift_ - sector_shift_;
  return l2_->Access(sector >> per_line_shift, static_cast<int>(sector & ((1u << per_line_shift) - 1)));
}

MemoryLevel CacheHierarchy::Access(int sm, std::uint64_t address) {
  const std::uint64_t offset = address - begin_;
  const std::uint64_t line = offset >> line_shift_;
  const int sector = static_cast<int>((offset >> sector_shift_) & ((1u << (line_shift_ - sector_shift_)) - 1));
  if (l1_[sm]->Access(line, sector)) return MemoryLevel::kL1;
  if (l2_->Access(line, sector)) return MemoryLevel::kL2;
  return MemoryLevel::kDram;
}

}  // namespace rc
