#pragma once
// List scheduling of warps onto a fixed number of slots (resident warps on
// an SM, or warp-buffer entries of an RT unit): each warp, in issue order,
// takes the slot that frees first and holds it for its duration. Returns the
// makespan. This is the latency-bound term of the first-order models: with
// every warp stalled on its own dependent chain, the SM finishes when the
// last slot does.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace rc {

// At least one slot. The slots are a binary min-heap of the times they
// free, whose top is replaced in place (one sift-down per warp rather than
// a pop and a push); which of several equally early slots a warp takes does
// not change the makespan.
inline std::uint64_t Makespan(const std::vector<std::uint64_t>& durations, int slots) {
  const std::size_t k = static_cast<std::size_t>(slots < 1 ? 1 : slots);
  std::uint64_t end = 0;
  if (durations.size() <= k) {  // every warp starts at once
    for (std::uint64_t d : durations) end = std::max(end, d);
    return end;
  }
  std::vector<std::uint64_t> free_at(k, 0);
  for (std::uint64_t d : durations) {
    const std::uint64_t finish = free_at[0] + d;
    end = std::max(end, finish);
    std::size_t i = 0;  // sift the replaced top down
    for (;;) {
      std::size_t child = 2 * i + 1;
      if (child >= k) break;
      if (child + 1 < k && free_at[child + 1] < free_at[child]) ++child;
      if (free_at[child] >= finish) break;
      free_at[i] = free_at[child];
      i = child;
    }
    free_at[i] = finish;
  }
  return end;
}

}  // namespace rc
