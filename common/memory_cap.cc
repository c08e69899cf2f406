#include "common/memory_cap.h"

#include <atomic>
#include <limits>
#include <unistd.h>

#include <fmt/format.h>

namespace rc {
namespace {

std::uint64_t PhysicalMemoryBytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES);
  const long page_size = ::sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page_size <= 0) return std::numeric_limits<std::uint64_t>::max();
  return static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page_size);
}

std::atomic<std::uint64_t>& Cap() {
  static std::atomic<std::uint64_t> cap{PhysicalMemoryBytes()};
  return cap;
}

}  // namespace

std::uint64_t MemoryCapBytes() { return Cap().load(); }
void SetMemoryCapBytes(std::uint64_t bytes) { Cap().store(bytes); }

std::uint64_t BytesFor(std::uint64_t count, std::uint64_t bytes_each) {
  if (bytes_each != 0 && count > std::numeric_limits<std::uint64_t>::max() / bytes_each)
    return std::numeric_limits<std::uint64_t>::max();
  return count * bytes_each;
}

std::string DescribeBytes(std::uint64_t bytes) {
  const double b = static_cast<double>(bytes);
  if (bytes >= (1ULL << 30)) return fmt::format("{:.2f} GiB", b / (1ULL << 30));
  if (bytes >= (1ULL << 20)) return fmt::format("{:.1f} MiB", b / (1ULL << 20));
  return fmt::format("{} bytes", bytes);
}

std::string DescribeOverCap(std::uint64_t need_bytes) {
  return "needs " + DescribeBytes(need_bytes) + ", more than the memory cap of " + DescribeBytes(MemoryCapBytes()) +
         " (the machine's memory by default; set it with rcbench --max-memory GIB)";
}

}  // namespace rc
