#include "robocore/ray_batch_lanes.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "common/cpu_features.h"
#include "robocore/ray_lane_state.h"

namespace rc {

std::string_view ToString(RayLaneIsa isa) { return isa == RayLaneIsa::kAvx512 ? "avx512" : "avx2"; }

const std::vector<RayLaneIsa>& HostRayLaneIsas() {
  static const std::vector<RayLaneIsa> isas = [] {
    std::vector<RayLaneIsa> v;
    if (CpuHasAvx2()) v.push_back(RayLaneIsa::kAvx2);
    if (CpuHasAvx512()) v.push_back(RayLaneIsa::kAvx512);
    return v;
  }();
  return isas;
}

bool RayLanesSupported() { return UseAvx2(); }

RayLaneIsa RayLaneIsaInUse() {
  if (!RayLanesSupported())
    throw std::logic_error("RayLaneIsaInUse: no lanes run here (check RayLanesSupported first)");
  return UseAvx512() ? RayLaneIsa::kAvx512 : RayLaneIsa::kAvx2;
}

bool RayLanesApply(const RayCastScene& scene) {
  if (!RayLanesSupported()) return false;
  // Signed 32-bit gather indices, and cell indices computed in 32 bits.
  return scene.grid().cell_count() + RayCastScene::kGatherPadding <=
         static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max());
}

void CastRayLanes(const RayCastScene& scene, const RayQuery* queries, std::size_t count, double max_range_m,
                  RayHit* hits, const LaneRecording* recording) {
  if (!RayLanesSupported()) throw std::logic_error("CastRayLanes: no lanes run here (check RayLanesApply first)");
  CastRayLanesIn(RayLaneIsaInUse(), scene, queries, count, max_range_m, hits, recording);
}

void CastRayLanesIn(RayLaneIsa isa, const RayCastScene& scene, const RayQuery* queries, std::size_t count,
                    double max_range_m, RayHit* hits, const LaneRecording* recording) {
  const std::vector<RayLaneIsa>& host = HostRayLaneIsas();
  if (std::find(host.begin(), host.end(), isa) == host.end())
    throw std::invalid_argument("CastRayLanesIn: this CPU does not run " + std::string(ToString(isa)));
  if (count == 0) return;
  const OccupancyGrid& grid = scene.grid();
  const long samples = ray_lanes::MarchSamples(grid, max_range_m);
  // Sample indices are 32-bit in the lanes.
  if (scene.method() == RayCastMethod::kMarch && samples >= std::numeric_limits<std::int32_t>::max()) {
    if (recording) throw std::logic_error("CastRayLanes: a recording needs the lanes (RayLanesApply)");
    for (std::size_t i = 0; i < count; ++i)
      hits[i] = CastRay(scene, queries[i].origin_x_m, queries[i].origin_y_m, queries[i].angle_rad, max_range_m);
    return;
  }
  ray_lanes::LaneScene lanes;
  if (scene.method() == RayCastMethod::kRayMarching)
    lanes.field = scene.distance_field()->values().data();
  else
    lanes.cells = scene.gather_cells().data();
  lanes.r = grid.resolution_m();
  lanes.max_range = max_range_m;
  lanes.jump_margin = (std::sqrt(2.0) + 0.5) * lanes.r;
  lanes.size_x = grid.size_x();
  lanes.size_y = grid.size_y();
  lanes.march_samples = scene.method() == RayCastMethod::kMarch ? static_cast<std::int32_t>(samples) : 0;
  lanes.cell_count = grid.cell_count();
  if (isa == RayLaneIsa::kAvx512)
    ray_lanes::CastLanesAvx512(scene.method(), lanes, queries, count, hits, recording);
  else
    ray_lanes::CastLanesAvx2(scene.method(), lanes, queries, count, hits, recording);
}

}  // namespace rc
