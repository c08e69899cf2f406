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

CacheHierarchy::CacheHierarchy(const GpuParams& gpu, std::uint64_t footprint_begin, std::uint64_t footprint_end)
    : begin_(footprint_begin), sector_shift_(Log2(gpu.sector_bytes)), line_shift_(Log2(gpu.line_bytes)) {
  if (footprint_end < footprint_begin) throw std::invalid_argument("CacheHierarchy: empty footprint");
  if (((footprint_end - footprint_begin) >> sector_shift_) >= (std::uint64_t{1} << 31))
    throw std::invalid_argument("CacheHierarchy: footprint beyond 2^31 sectors");
  // Lines are numbered from the footprint's first line, so every structure
  // is sized by the footprint, not by the address space.
  begin_ = footprint_begin >> line_shift_ << line_shift_;
  const std::uint64_t line_bytes = std::uint64_t{1} << line_shift_;
  lines_ = (footprint_end - begin_ + line_bytes - 1) >> line_shift_;
  per_line_shift_ = line_shift_ - sector_shift_;
  l1_lines_ = static_cast<std::uint64_t>(gpu.l1_bytes) >> line_shift_;
  l1_.resize(static_cast<std::size_t>(gpu.sms));
  l2_.emplace_back(lines_, per_line_shift_, static_cast<std::uint64_t>(gpu.l2_bytes) >> line_shift_, gpu.l2_ways);
  const char* kFits = "cold (footprint fits: compulsory misses only)";
  l1_model_ = CacheLevel::Fits(lines_, l1_lines_) ? kFits : "lru (fully associative)";
  l2_model_ = l2_.front().cold() ? kFits : "lru (set associative)";
  latency_[0] = gpu.l1_latency_cycles;
  latency_[1] = latency_[0] + gpu.l2_latency_cycles;
  latency_[2] = latency_[1] + gpu.DramExtraCycles();
}

CacheLevel& CacheHierarchy::L1(int sm) {
  std::unique_ptr<CacheLevel>& level = l1_[static_cast<std::size_t>(sm)];
  if (!level) level = std::make_unique<CacheLevel>(lines_, per_line_shift_, l1_lines_, 0);
  return *level;
}

MemoryLevel CacheHierarchy::Access(int sm, std::uint64_t address) {
  const std::uint32_t sector = SectorNumber(address);
  if (L1(sm).Access(sector)) return MemoryLevel::kL1;
  if (L2().Access(sector)) return MemoryLevel::kL2;
  return MemoryLevel::kDram;
}

}  // namespace rc
