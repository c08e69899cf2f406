#pragma once
// Tunables of the Monte Carlo localizer, with units and ranges. Defaults are
// nav2 AMCL's where it has one (REFERENCE.md section 4), otherwise stated.
#include <cstdint>
#include <string>

#include "workloads/delibot/motion_model.h"
#include "workloads/delibot/sensor_model.h"

namespace rc {

struct MclOptions {
  int particle_count = 2000;          // [1, 10^7]
  std::uint64_t seed = 1;
  OdometryMotionNoise motion;
  BeamSelection beams{6};             // every 6th beam: 30 of 180 (nav2 uses 60); [1, beam count]
  double resample_ess_fraction = 0.5; // resample when ESS < fraction * N; (0, 1]
  // Augmented MCL (Probabilistic Robotics, Table 8.3): random particles are
  // injected when the short-term average likelihood falls below the
  // long-term one. alpha_slow < alpha_fast; both 0 disables injection.
  double alpha_slow = 0.001;          // nav2's suggested recovery_alpha_slow
  double alpha_fast = 0.1;            // nav2's suggested recovery_alpha_fast
  // A sensor update runs only after the odometry has moved this far since
  // the previous one (AMCL's update_min_d / update_min_a); 0 = every scan.
  // Repeated updates with the same scan while standing still make the filter
  // overconfident and starve it of diversity.
  double update_min_d_m = 0.05;
  double update_min_a_rad = 0.05;
  double estimate_kernel_radius_m = 1.0;  // mean-shift radius of the point estimate
  // Record every ray's node fetches (robocore/kernel_record.h) so that the
  // backends can price the update; off, the kernel runs without the hook.
  bool record_kernel = false;

  bool IsValid(std::string* error) const;
};

}  // namespace rc
