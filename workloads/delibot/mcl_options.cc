#include "workloads/delibot/mcl_options.h"

namespace rc {

bool MclOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& what) {
    if (error) *error = what;
    return false;
  };
  if (particle_count < 1 || particle_count > 10000000) return fail("particles must be in [1, 10^7]");
  if (initial_particle_count != 0 &&
      (initial_particle_count < particle_count || initial_particle_count > 10000000))
    return fail("initial particles must be 0 or in [particles, 10^7]");
  if (beams.beam_step < 1) return fail("beam step must be >= 1");
  if (!(resample_ess_fraction > 0.0 && resample_ess_fraction <= 1.0))
    return fail("resample ESS fraction must be in (0, 1]");
  if (!(alpha_slow >= 0.0 && alpha_fast >= 0.0 && alpha_slow <= 1.0 && alpha_fast <= 1.0))
    return fail("recovery alphas must be in [0, 1]");
  if (alpha_slow > 0.0 && !(alpha_fast > alpha_slow))
    return fail("alpha_fast must exceed alpha_slow for recovery to mean anything");
  if (injection_check_updates < 0 || injection_check_updates > 1000)
    return fail("injection check window must be in [0, 1000] sensor updates");
  if (hypothesis_floor.min_particles < 0 || hypothesis_floor.min_particles > particle_count / 2)
    return fail("hypothesis floor must be in [0, particles / 2] particles");
  if (max_particle_count != 0 &&
      (max_particle_count < particle_count || max_particle_count > 10000000))
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

}  // namespace rc
