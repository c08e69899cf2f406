// BeamReadingDensity (the beam model with its per-reading terms computed once
// per scan) against BeamLogDensity: bit-identical for every kind of reading
// and expected range, under the default and under other parameters.
#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "common/random_stream.h"
#include "workloads/delibot/beam_sensor_model.h"

namespace rc {
namespace {

void ExpectBitIdentical(const BeamModelParams& p, std::uint64_t seed) {
  RandomStream s(seed, StreamPurpose::kTest, 0, 0);
  std::vector<double> readings = {0.0, 1e-9, 0.05, 1.0, p.max_range_m * 0.999, p.max_range_m, p.max_range_m + 3.0};
  for (int i = 0; i < 200; ++i) readings.push_back(s.Uniform(0.0, p.max_range_m * 1.1));
  for (double z : readings) {
    const BeamReadingDensity reading(p, z);
    std::vector<double> expected_ranges = {0.0, z, static_cast<float>(z), p.max_range_m, 1e-6};
    for (int j = 0; j < 200; ++j) expected_ranges.push_back(static_cast<float>(s.Uniform(0.0, p.max_range_m)));
    for (double z_star : expected_ranges) {
      const double a = reading.LogDensity(z_star), b = BeamLogDensity(p, z, z_star);
      ASSERT_EQ(std::memcmp(&a, &b, sizeof a), 0) << "z " << z << " z* " << z_star << ": " << a << " vs " << b;
    }
  }
}

TEST(BeamReadingDensityTest, BitIdenticalToBeamLogDensity) {
  ExpectBitIdentical(BeamModelParams{}, 1);
  BeamModelParams other;
  other.z_hit = 0.8;
  other.z_short = 0.1;
  other.z_max = 0.02;
  other.z_rand = 0.08;
  other.sigma_hit_m = 0.05;
  other.lambda_short_per_m = 1.3;
  other.max_range_m = 30.0;
  ExpectBitIdentical(other, 2);
  BeamModelParams no_short = other;
  no_short.z_short = 0.0;
  no_short.z_max = 0.0;
  ExpectBitIdentical(no_short, 3);
}

}  // namespace
}  // namespace rc
