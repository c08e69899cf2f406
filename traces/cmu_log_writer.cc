#include "traces/cmu_log_writer.h"

#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include <fmt/format.h>

#include "common/atomic_file.h"
#include "common/input_error.h"
#include "traces/cmu_laser_geometry.h"

namespace rc {
namespace {

constexpr double kAngleTolerance_rad = 1e-9;

void RequireCmuGeometry(const SensorTrace& trace) {
  const LaserGeometry cmu = CmuLaserGeometry();
  const LaserGeometry& g = trace.geometry;
  if (g.beam_count != cmu.beam_count || std::abs(g.angle_min_rad - cmu.angle_min_rad) > kAngleTolerance_rad ||
      std::abs(g.angle_increment_rad - cmu.angle_increment_rad) > kAngleTolerance_rad) {
    throw UsageError(
        fmt::format("cannot write '{}' as a CMU log: its laser has {} beams from {:.6f} rad every "
                    "{:.6f} rad; a CMU log implies 180 beams from -pi/2 every pi/180",
                    trace.source_path, g.beam_count, g.angle_min_rad, g.angle_increment_rad));
  }
}

// The shortest plain decimal for a range (cm) that reads back (cm / 100 ->
// float) to exactly `range_m`: whole cm for real SICK data. Scientific
// notation at 9 significant digits, which always round-trips a float, is the
// fallback for values too small for 6 decimals.
std::string FormatRangeCm(float range_m) {
  const double cm = MetresToCentimetres(range_m);
  for (int decimals = 0; decimals <= 6; ++decimals) {
    std::string text = fmt::format("{:.{}f}", cm, decimals);
    if (static_cast<float>(CentimetresToMetres(std::strtod(text.c_str(), nullptr))) == range_m) return text;
  }
  return fmt::format("{:.9g}", cm);
}

void CheckScan(const SensorTrace& trace, std::size_t k, double previous_time_s) {
  const LaserScan& scan = trace.scans[k];
  const std::string where = "scan " + std::to_string(k) + " of '" + trace.source_path + "'";
  if (scan.ranges_m.size() != static_cast<std::size_t>(trace.geometry.beam_count))
    throw std::invalid_argument(where + " has " + std::to_string(scan.ranges_m.size()) + " ranges for a " +
                                std::to_string(trace.geometry.beam_count) + "-beam laser");
  if (!std::isfinite(scan.time_s) || !std::isfinite(scan.odometry.x) || !std::isfinite(scan.odometry.y) ||
      !std::isfinite(scan.odometry.theta))
    throw std::invalid_argument(where + " has a non-finite pose or time");
  if (k > 0 && scan.time_s < previous_time_s)
    throw std::invalid_argument(where + " is earlier than the scan before it");
  const double cmu_max_m = CmuLaserGeometry().max_range_m;
  for (std::size_t b = 0; b < scan.ranges_m.size(); ++b) {
    const float r = scan.ranges_m[b];
    if (!std::isfinite(r) || r < 0.0f)
      throw std::invalid_argument(where + " range " + std::to_string(b + 1) + " is NaN, inf or negative");
    if (r < trace.geometry.max_range_m && r >= cmu_max_m)
      throw UsageError(where + " range " + std::to_string(b + 1) + " is a valid reading of " + std::to_string(r) +
                       " m, beyond what a CMU log can carry (< 81.83 m)");
  }
}

}  // namespace

void WriteCmuLog(const SensorTrace& trace, const std::string& path, const CmuLogWriteOptions& options) {
  RequireCmuGeometry(trace);
  for (std::size_t k = 0; k < trace.scans.size(); ++k) CheckScan(trace, k, k > 0 ? trace.scans[k - 1].time_s : 0.0);

  AtomicFile file(path);
  std::ostream& out = file.stream();
  const double offset_m = trace.geometry.offset_forward_m;
  const double cmu_max_m = CmuLaserGeometry().max_range_m;
  const std::string no_return = FormatRangeCm(static_cast<float>(CentimetresToMetres(kCmuNoReturnCm)));
  for (const LaserScan& scan : trace.scans) {
    const Pose2& p = scan.odometry;
    const double x_cm = MetresToCentimetres(p.x);
    const double y_cm = MetresToCentimetres(p.y);
    if (options.odometry_records) {
      out << fmt::format("O {:.6f} {:.6f} {:.6f} {:.6f}\n", x_cm, y_cm, p.theta, scan.time_s);
    }
    const double xl_cm = MetresToCentimetres(p.x + offset_m * std::cos(p.theta));
    const double yl_cm = MetresToCentimetres(p.y + offset_m * std::sin(p.theta));
    out << fmt::format("L {:.6f} {:.6f} {:.6f} {:.6f} {:.6f} {:.6f}", x_cm, y_cm, p.theta, xl_cm, yl_cm, p.theta);
    for (float r : scan.ranges_m) {
      // A no-return of a shorter-range trace must stay a no-return for a CMU
      // reader; readings already past 81.83 m (the SICK codes) are kept as is.
      const bool translate = r >= trace.geometry.max_range_m && r < cmu_max_m;
      out << ' ' << (translate ? no_return : FormatRangeCm(r));
    }
    out << fmt::format(" {:.6f}\n", scan.time_s);
  }
  file.Commit();
}

}  // namespace rc
