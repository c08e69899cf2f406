#include "workloads/delibot/start_probe.h"

#include <algorithm>

#include "backends/scheduler/backend_ledger.h"
#include "common/random_stream.h"

namespace rc {

std::size_t StartProbePoses(std::size_t first_update_particles, int beams_per_particle) {
  const auto beams = static_cast<std::size_t>(std::max(1, beams_per_particle));
  const std::size_t queries = BackendLedger::StartProbeQueries(first_update_particles * beams);
  return std::max<std::size_t>(1, std::min(first_update_particles, queries / beams));
}

KernelRecord CastStartProbe(const MonteCarloLocalizer& mcl, const RayCastScene& scene, const LaserGeometry& geometry,
                            const BeamSelection& beams, double max_range_m, std::size_t poses, std::uint64_t seed,
                            const RecordOptions& record_options) {
  const int per_pose = beams.Count(geometry.beam_count);
  RayBatch batch;
  batch.max_range_m = max_range_m;
  batch.queries.resize(poses * static_cast<std::size_t>(per_pose));
  for (std::size_t i = 0; i < poses; ++i) {
    RandomStream stream(seed, StreamPurpose::kStartProbe, 0, i);
    const Pose2 sensor = SensorPose(mcl.DrawInitialPose(stream), geometry);
    for (int k = 0; k < per_pose; ++k)
      batch.queries[i * static_cast<std::size_t>(per_pose) + k] = BeamQuery(sensor, geometry, beams, k);
  }
  std::vector<RayHit> hits;
  KernelRecord record;
  CastRayBatchRecorded(scene, batch, hits, record, record_options);
  return record;
}

}  // namespace rc
