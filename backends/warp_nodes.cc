#include "backends/warp_nodes.h"

#include <algorithm>
#include <stdexcept>

#include "common/avx512_warnings.h"

#if defined(__x86_64__)
RC_AVX512_WARNINGS_OFF
#include <immintrin.h>
#endif

#include "common/cpu_features.h"

namespace rc {

void CountWarpNodesScalar(const std::uint64_t* offsets, std::size_t queries, std::size_t warp_size,
                          std::uint32_t* steps, std::uint64_t* lane_nodes) {
  for (std::size_t w = 0, lo = 0; lo < queries; ++w, lo += warp_size) {
    const std::size_t hi = std::min(queries, lo + warp_size);
    std::uint64_t most = 0;
    for (std::size_t q = lo; q < hi; ++q) most = std::max(most, offsets[q + 1] - offsets[q]);
    steps[w] = static_cast<std::uint32_t>(most);
    lane_nodes[w] = offsets[hi] - offsets[lo];
  }
}

#if defined(__x86_64__)

// Eight queries a step, the last step of a warp masked (masked lanes count
// zero nodes); the warp's maximum by one reduction.
__attribute__((target("avx512f"))) void CountWarpNodesLanes(const std::uint64_t* offsets, std::size_t queries,
                                                            std::size_t warp_size, std::uint32_t* steps,
                                                            std::uint64_t* lane_nodes) {
  for (std::size_t w = 0, lo = 0; lo < queries; ++w, lo += warp_size) {
    const std::size_t hi = std::min(queries, lo + warp_size);
    __m512i most = _mm512_setzero_si512();
    for (std::size_t q = lo; q < hi; q += 8) {
      const auto in = static_cast<__mmask8>(hi - q >= 8 ? 0xFF : (1u << (hi - q)) - 1);
      const __m512i begin = _mm512_maskz_loadu_epi64(in, offsets + q);
      const __m512i end = _mm512_maskz_loadu_epi64(in, offsets + q + 1);
      most = _mm512_max_epu64(most, _mm512_sub_epi64(end, begin));
    }
    steps[w] = static_cast<std::uint32_t>(_mm512_reduce_max_epu64(most));
    lane_nodes[w] = offsets[hi] - offsets[lo];
  }
}

RC_AVX512_WARNINGS_ON

#else  // not x86-64: never called (UseAvx512() is false).

void CountWarpNodesLanes(const std::uint64_t*, std::size_t, std::size_t, std::uint32_t*, std::uint64_t*) {
  throw std::logic_error("CountWarpNodesLanes: AVX-512 exists only on x86-64");
}

#endif

void CountWarpNodes(const std::uint64_t* offsets, std::size_t queries, std::size_t warp_size, std::uint32_t* steps,
                    std::uint64_t* lane_nodes) {
  if (warp_size == 0) throw std::invalid_argument("CountWarpNodes: warp_size must be at least 1");
  if (UseAvx512())
    CountWarpNodesLanes(offsets, queries, warp_size, steps, lane_nodes);
  else
    CountWarpNodesScalar(offsets, queries, warp_size, steps, lane_nodes);
}

WarpNodeCounts CountWarpNodes(const std::vector<std::uint64_t>& fetch_offsets, std::size_t warp_size) {
  if (warp_size == 0) throw std::invalid_argument("CountWarpNodes: warp_size must be at least 1");
  const std::size_t queries = fetch_offsets.size() - 1;
  WarpNodeCounts counts;
  counts.steps.resize((queries + warp_size - 1) / warp_size);
  counts.lane_nodes.resize(counts.steps.size());
  // In runs of whole warps spread over the threads: a warp's counts depend
  // on its own queries alone.
  constexpr std::size_t kRunWarps = 1024;
  const std::size_t warps = counts.steps.size();
  const long runs = static_cast<long>((warps + kRunWarps - 1) / kRunWarps);
#pragma omp parallel for schedule(static)
  for (long r = 0; r < runs; ++r) {
    const std::size_t first = static_cast<std::size_t>(r) * kRunWarps, last = std::min(warps, first + kRunWarps);
    const std::size_t begin = first * warp_size, end = std::min(queries, last * warp_size);
    CountWarpNodes(fetch_offsets.data() + begin, end - begin, warp_size, counts.steps.data() + first,
                   counts.lane_nodes.data() + first);
  }
  return counts;
}

}  // namespace rc
