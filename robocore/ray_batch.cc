#include "robocore/ray_batch.h"

namespace rc {

void CastRayBatch(const RayCastScene& scene, const RayBatch& batch, std::vector<RayHit>& hits) {
  const long n = static_cast<long>(batch.queries.size());
  hits.resize(batch.queries.size());
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; ++i) {
    const RayQuery& q = batch.queries[i];
    hits[i] = CastRay(scene, q.origin_x_m, q.origin_y_m, q.angle_rad, batch.max_range_m);
  }
}

std::uint64_t TotalNodes(const std::vector<RayHit>& hits) {
  std::uint64_t total = 0;
  for (const RayHit& h : hits) total += h.nodes;
  return total;
}

}  // namespace rc
