#pragma once
// Angle helpers: headings are wrapped to (-pi, pi] and averaged on the circle
// (RoWild averages headings arithmetically, so -179 deg and +179 deg average
// to 0 instead of 180).
#include <cmath>

namespace rc {

inline constexpr double kPi = 3.14159265358979323846;

inline double WrapAngle(double a) {
  a = std::remainder(a, 2.0 * kPi);  // in [-pi, pi]
  if (a <= -kPi) a += 2.0 * kPi;
  return a;
}

// Accumulates weighted headings as unit vectors.
class CircularMean {
 public:
  void Add(double angle_rad, double weight = 1.0) {
    sum_cos_ += weight * std::cos(angle_rad);
    sum_sin_ += weight * std::sin(angle_rad);
    total_weight_ += weight;
  }
  double Mean() const { return std::atan2(sum_sin_, sum_cos_); }
  // Mean resultant length in [0, 1]: 1 = all headings equal.
  double Resultant() const { return total_weight_ > 0 ? std::hypot(sum_cos_, sum_sin_) / total_weight_ : 0.0; }

 private:
  double sum_cos_ = 0.0;
  double sum_sin_ = 0.0;
  double total_weight_ = 0.0;
};

struct Pose2 {
  double x = 0.0;      // m
  double y = 0.0;      // m
  double theta = 0.0;  // rad
};

}  // namespace rc
