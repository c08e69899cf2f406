#include "robocore/ray_batch.h"

#include <algorithm>

#include "robocore/ray_batch_lanes.h"

namespace rc {
namespace {

// Queries per work unit: large enough that a unit's start-up (filling the
// lanes) and the OpenMP hand-out are negligible, small enough that two
// threads on a shared machine even out (dynamic schedule).
constexpr long kQueriesPerUnit = 2048;

void CastRange(const RayCastScene& scene, const RayBatch& batch, bool lanes, long begin, long end, RayHit* hits) {
  if (lanes) {
    CastRayLanes(scene, batch.queries.data() + begin, static_cast<std::size_t>(end - begin), batch.max_range_m,
                 hits + begin);
    return;
  }
  for (long i = begin; i < end; ++i) {
    const RayQuery& q = batch.queries[i];
    hits[i] = CastRay(scene, q.origin_x_m, q.origin_y_m, q.angle_rad, batch.max_range_m);
  }
}

}  // namespace

void CastRayBatch(const RayCastScene& scene, const RayBatch& batch, std::vector<RayHit>& hits) {
  hits.resize(batch.queries.size());
  CastRayBatchRange(scene, batch, 0, batch.queries.size(), hits);
}

void CastRayBatchRange(const RayCastScene& scene, const RayBatch& batch, std::size_t begin, std::size_t end,
                       std::vector<RayHit>& hits) {
  const long first = static_cast<long>(begin), last = static_cast<long>(end);
  const long units = (last - first + kQueriesPerUnit - 1) / kQueriesPerUnit;
  const bool lanes = RayLanesApply(scene);
#pragma omp parallel for schedule(dynamic, 1) if (units > 1)
  for (long u = 0; u < units; ++u) {
    const long lo = first + u * kQueriesPerUnit;
    CastRange(scene, batch, lanes, lo, std::min(last, lo + kQueriesPerUnit), hits.data());
  }
}

void CastRaySlice(const RayCastScene& scene, const RayBatch& batch, std::size_t begin, std::size_t end,
                  std::vector<RayHit>& hits) {
  CastRange(scene, batch, RayLanesApply(scene), static_cast<long>(begin), static_cast<long>(end), hits.data());
}

std::uint64_t TotalNodes(const std::vector<RayHit>& hits) {
  std::uint64_t total = 0;
  for (const RayHit& h : hits) total += h.nodes;
  return total;
}

}  // namespace rc
