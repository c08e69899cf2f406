#pragma once
// Splits a particle set into hypotheses: groups of particles that are
// connected through occupied bins of a pose grid (x, y, heading). Two
// look-alike doors 6 m apart, or the same corridor faced both ways, are
// different hypotheses; one particle cloud a few decimetres wide is one.
// AMCL clusters its particles the same way (kd-tree leaves at 0.5 m / 10 deg,
// joined when adjacent); coarser bins here, because a hypothesis is what the
// resampler must keep alive, not a peak to report.
#include <cstddef>
#include <vector>

#include "common/angles.h"

namespace rc {

struct HypothesisClusters {
  std::vector<int> cluster_of;  // cluster index of each particle, in [0, count)
  int count = 0;                // clusters, numbered in order of their first particle
};

// Bins are xy_bin_m square in position and 2 pi / heading_bins in heading;
// bins that touch (26-neighbourhood, headings wrapping around) join. Throws
// std::invalid_argument for a non-positive bin size or heading_bins < 1.
HypothesisClusters ClusterHypotheses(const std::vector<Pose2>& particles, double xy_bin_m, int heading_bins);

}  // namespace rc
