#pragma once
// The filter's point estimate. During global localization the particle set
// is multimodal and its overall mean can sit in a wall between two modes, so
// the estimate is the weighted mean of the dominant mode: a few mean-shift
// iterations with a flat kernel, started at the heaviest particle. Headings
// are averaged on the circle.
#include <vector>

#include "common/angles.h"

namespace rc {

struct PoseEstimate {
  Pose2 pose;
  double mode_weight = 0.0;  // total normalized weight inside the mode's kernel
  double spread_m = 0.0;     // weighted RMS distance of all particles from the estimate (m)
};

// normalized_log_weights: log weights summing to 1 in the linear domain.
PoseEstimate EstimatePose(const std::vector<Pose2>& particles, const std::vector<double>& normalized_log_weights,
                          double kernel_radius_m = 1.0);

}  // namespace rc
