#include "workloads/delibot/delibot_memory.h"

#include <algorithm>

#include "common/memory_cap.h"
#include "robocore/ray_batch.h"
#include "robocore/ray_cast.h"

namespace rc {

std::uint64_t DelibotMemoryLowerBound(const DelibotSettings& settings, int beam_count) {
  const MclOptions& m = settings.mcl;
  const std::uint64_t particles =
      static_cast<std::uint64_t>(std::max({m.particle_count, m.initial_particle_count, m.max_particle_count}));
  const std::uint64_t per_particle = sizeof(Pose2) + 2 * sizeof(double);
  std::uint64_t per_ray = 0;
  if (CastsRays(settings.sensor_model)) {  // the staged model casts once one hypothesis is left
    per_ray = sizeof(RayQuery) + sizeof(RayHit);
    if (settings.price_backends) per_ray += 2 * sizeof(std::uint64_t) + sizeof(std::uint8_t);
  }
  const std::uint64_t rays = BytesFor(particles, static_cast<std::uint64_t>(m.beams.Count(beam_count)));
  const std::uint64_t ray_bytes = BytesFor(rays, per_ray);
  const std::uint64_t particle_bytes = BytesFor(particles, per_particle);
  return ray_bytes > UINT64_MAX - particle_bytes ? UINT64_MAX : ray_bytes + particle_bytes;
}

}  // namespace rc
