#include "workloads/delibot/returns_beyond_reach.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace rc {

double ReturnsBeyondReach::QuantileM(double q) const {
  const double wanted = q * static_cast<double>(returns);
  long below = 0;
  for (std::size_t i = 0; i < bins.size(); ++i) {
    below += bins[i];
    if (static_cast<double>(below) >= wanted) return static_cast<double>(i + 1) / kReachBinsPerM;
  }
  return static_cast<double>(bins.size()) / kReachBinsPerM;
}

ReturnsBeyondReach CountReturnsBeyondReach(ScanSource& scans, double model_max_range_m) {
  ReturnsBeyondReach count;
  const double sensor_max_m = scans.geometry().max_range_m;
  count.bins.assign(static_cast<std::size_t>(std::ceil(sensor_max_m * kReachBinsPerM)) + 1, 0);
  scans.Rewind();
  LaserScan scan;
  while (scans.Next(scan))
    for (const float r : scan.ranges_m) {
      if (!(r < sensor_max_m) || r < 0.0f) continue;  // no return (the readers refuse NaN and negatives)
      ++count.returns;
      count.beyond += r >= model_max_range_m;
      count.longest_m = std::max(count.longest_m, static_cast<double>(r));
      ++count.bins[std::min(count.bins.size() - 1, static_cast<std::size_t>(r * kReachBinsPerM))];
    }
  scans.Rewind();
  return count;
}

std::string FitReachToTrace(double& max_range_m, const ReturnsBeyondReach& count, bool max_range_given) {
  if (count.Fraction() <= kBeyondReachFraction) return "";
  const double beyond_percent = 100.0 * count.Fraction();
  if (max_range_given)
    return fmt::format(
        "note: {:.0f}% of the trace's returns lie at or beyond --max-range {:g} m (the longest {:.1f} m), and the "
        "models count them as no return (docs/delibot.md, \"Max range\")\n",
        beyond_percent, max_range_m, count.longest_m);
  const double default_m = max_range_m;
  max_range_m = std::max(max_range_m, count.QuantileM(kWidenedReachQuantile));
  return fmt::format(
      "note: {:.0f}% of the trace's returns lie beyond {:g} m: the models reach {:.1f} m, past {:.0f}% of them "
      "(--max-range sets the reach; docs/delibot.md, \"Max range\")\n",
      beyond_percent, default_m, max_range_m, 100.0 * kWidenedReachQuantile);
}

}  // namespace rc
