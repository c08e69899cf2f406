#include "workloads/delibot/returns_beyond_reach.h"

#include <algorithm>

#include <fmt/format.h>

namespace rc {

ReturnsBeyondReach CountReturnsBeyondReach(ScanSource& scans, double model_max_range_m) {
  ReturnsBeyondReach count;
  const double sensor_max_m = scans.geometry().max_range_m;
  scans.Rewind();
  LaserScan scan;
  while (scans.Next(scan))
    for (const float r : scan.ranges_m) {
      if (!(r < sensor_max_m)) continue;  // no return (or not a number: the reader refuses those)
      ++count.returns;
      count.beyond += r >= model_max_range_m;
      count.longest_m = std::max(count.longest_m, static_cast<double>(r));
    }
  scans.Rewind();
  return count;
}

std::string BeyondReachNote(const ReturnsBeyondReach& count, double model_max_range_m) {
  if (count.Fraction() <= kBeyondReachNoteFraction) return "";
  return fmt::format(
      "note: {:.0f}% of the trace's returns lie at or beyond --max-range {:g} m (the longest {:.1f} m), and the "
      "models count them as no return; a --max-range that reaches them uses them (docs/delibot.md, \"Max range\")\n",
      100.0 * count.Fraction(), model_max_range_m, count.longest_m);
}

}  // namespace rc
