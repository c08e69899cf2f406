#pragma once
// List scheduling of warps onto a fixed number of slots (resident warps on
// an SM, or warp-buffer entries of an RT unit): each warp, in issue order,
// takes the slot that frees first and holds it for its duration. Returns the
// makespan. This is the latency-bound term of the first-order models: with
// every warp stalled on its own dependent chain, the SM finishes when the
// last slot does.
#include <cstdint>
#include <functional>
#include <queue>
#include <vector>

namespace rc {

inline std::uint64_t Makespan(const std::vector<std::uint64_t>& durations, int slots) {
  std::priority_queue<std::uint64_t, std::vector<std::uint64_t>, std::greater<>> free_at;
  for (int i = 0; i < slots; ++i) free_at.push(0);
  std::uint64_t end = 0;
  for (std::uint64_t d : durations) {
    const std::uint64_t start = free_at.top();
    free_at.pop();
    free_at.push(start + d);
    end = std::max(end, start + d);
  }
  return end;
}

}  // namespace rc
