#pragma once
// A batch of ray-casting queries of one kernel, in launch order. For DeliBot
// the order is particle-major, beam-minor, one query per thread, as the CUDA
// kernels launch them. Backends take a batch and return the same hits; they
// differ only in what they say the batch cost.
#include <cstdint>
#include <vector>

#include "robocore/ray_cast.h"

namespace rc {

struct RayQuery {
  double origin_x_m = 0.0;
  double origin_y_m = 0.0;
  double angle_rad = 0.0;
};

struct RayBatch {
  std::vector<RayQuery> queries;
  double max_range_m = 10.0;
};

// Functional execution on the host, parallel over units of queries with
// OpenMP; the result does not depend on the thread count (each query is
// independent). The queries run in SIMD lanes (AVX-512 or AVX2) where the CPU has them
// (ray_batch_lanes.h); every hit equals CastRay's, bit for bit, on either
// path.
void CastRayBatch(const RayCastScene& scene, const RayBatch& batch, std::vector<RayHit>& hits);

// CastRayBatch for queries [begin, end) of `batch`, into hits [begin, end)
// (hits must already hold batch.queries.size() entries).
void CastRayBatchRange(const RayCastScene& scene, const RayBatch& batch, std::size_t begin, std::size_t end,
                       std::vector<RayHit>& hits);

// Casts queries [begin, end) of `batch` into hits [begin, end) on the
// calling thread (hits must already hold batch.queries.size() entries): the
// same hits as CastRayBatch, for a caller that runs its own parallel loop.
void CastRaySlice(const RayCastScene& scene, const RayBatch& batch, std::size_t begin, std::size_t end,
                  std::vector<RayHit>& hits);

// Sum of hits[i].nodes.
std::uint64_t TotalNodes(const std::vector<RayHit>& hits);

}  // namespace rc
