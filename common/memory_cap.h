#pragma once
// The memory a run may plan for. Sizes that the input decides (a map's
// cells, the particle count, a batch) are checked against this cap before
// anything is allocated, so an impossible size is refused with its numbers
// instead of ending in std::bad_alloc or the kernel's OOM killer.
//
// Default: the machine's physical memory (sysconf). `rcbench --max-memory
// GIB` lowers or raises it for the process: one limit for the whole run,
// like an rlimit, which is why it lives here and not in each loader's
// options.
#include <cstdint>
#include <string>

namespace rc {

std::uint64_t MemoryCapBytes();
void SetMemoryCapBytes(std::uint64_t bytes);

// count * bytes_each, saturating at UINT64_MAX instead of wrapping.
std::uint64_t BytesFor(std::uint64_t count, std::uint64_t bytes_each);

// "1.50 GiB" / "512.0 MiB" / "12 bytes".
std::string DescribeBytes(std::uint64_t bytes);

// "N bytes (needs ...) exceeds the memory cap of ... (rcbench --max-memory)":
// the common tail of every refusal, so they all read alike.
std::string DescribeOverCap(std::uint64_t need_bytes);

}  // namespace rc
