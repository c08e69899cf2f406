#include "workloads/delibot/mcl_options.h"

#include <algorithm>
#include <cmath>

namespace rc {

bool MclOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& what) {
    if (error) *error = what;
    return false;
  };
  if (particle_count < 1 || particle_count > 10000000) return fail("particles must be in [1, 10^7]");
  if (initial_particle_count != 0 && initial_particle_count != kAutoInitialParticles &&
      (initial_particle_count < particle_count || initial_particle_count > 10000000))
    return fail("initial particles must be auto, 0 or in [particles, 10^7]");
  if (tracking_after_single_updates < 1 || tracking_after_single_updates > 1000)
    return fail("tracking stage delay must be in [1, 1000] sensor updates");
  if (beams.beam_step < 1) return fail("beam step must be >= 1");
  if (!(resample_ess_fraction > 0.0 && resample_ess_fraction <= 1.0))
    return fail("resample ESS fraction must be in (0, 1]");
  if (!(alpha_slow >= 0.0 && alpha_fast >= 0.0 && alpha_slow <= 1.0 && alpha_fast <= 1.0))
    return fail("recovery alphas must be in [0, 1]");
  if (alpha_slow > 0.0 && !(alpha_fast > alpha_slow))
    return fail("alpha_fast must exceed alpha_slow for recovery to mean anything");
  if (injection_check_updates < 0 || injection_check_updates > 1000)
    return fail("injection check window must be in [0, 1000] sensor updates");
  if (claim_audit_scans < 0 || claim_audit_scans > 1000)
    return fail("claim audit scans must be in [0, 1000] sensor updates");
  if (hypothesis_floor.min_particles < 0 || hypothesis_floor.min_particles > particle_count / 2)
    return fail("hypothesis floor must be in [0, particles / 2] particles");
  if (max_particle_count != 0 && (max_particle_count < particle_count || max_particle_count > 10000000))
    return fail("max particles must be 0 or in [particles, 10^7]");
  if (max_particle_count != 0 && hypothesis_floor.min_particles == 0)
    return fail("max particles grows the set only to keep floored hypotheses: it needs a hypothesis floor");
  if (!(hypothesis_floor.window_nats >= 0.0 && hypothesis_floor.window_nats <= 1e4))
    return fail("hypothesis window must be in [0, 10^4] nats");
  if (hypothesis_heading_bins < 1 || hypothesis_heading_bins > 360)
    return fail("hypothesis heading bins must be in [1, 360]");
  if (!(update_min_d_m >= 0.0 && update_min_a_rad >= 0.0)) return fail("update thresholds must be >= 0");
  if (!(estimate_kernel_radius_m > 0.0)) return fail("estimate kernel radius must be > 0 m");
  const auto& m = motion;
  if (!(m.alpha1 >= 0 && m.alpha2 >= 0 && m.alpha3 >= 0 && m.alpha4 >= 0))
    return fail("motion noise alphas must be >= 0");
  return true;
}

std::size_t InitialParticleCount(const MclOptions& options, double free_area_m2) {
  const auto base = static_cast<std::size_t>(options.particle_count);
  if (options.initial_particle_count != kAutoInitialParticles)
    return std::max(base, static_cast<std::size_t>(std::max(0, options.initial_particle_count)));
  // Uniform over free area x 2 pi of heading; the neighbourhood of a pose is
  // a disc of radius kAutoInitialNearXyM times 2 kAutoInitialNearThetaRad.
  constexpr double kPi = 3.14159265358979323846;
  const double neighbourhood = kPi * kAutoInitialNearXyM * kAutoInitialNearXyM * 2.0 * kAutoInitialNearThetaRad;
  const double wanted = std::ceil(kAutoInitialNearPose * free_area_m2 * 2.0 * kPi / neighbourhood);
  return std::clamp(static_cast<std::size_t>(std::min(wanted, 1e9)), base,
                    std::max(base, static_cast<std::size_t>(kAutoInitialParticlesCap)));
}

}  // namespace rc
