#include "workloads/rcbench/trace_lines.h"

#include <fmt/format.h>

#include "traces/record_fields.h"

namespace rc {

void PrintTraceLines(std::ostream& out, std::ostream& warnings, const ScanSource& trace, const TraceReadStats& stats,
                     bool mount_given) {
  const std::string& path = trace.source_path();
  const LaserGeometry& geometry = trace.geometry();
  std::string mount;
  const LaserMountStats& m = stats.laser_mount;
  if (mount_given)
    mount = fmt::format("laser {:.4f} m ahead (--laser-offset)", geometry.offset_forward_m);
  else if (m.samples > 0)
    mount =
        fmt::format("laser {:.4f} m ahead, measured from the file's laser poses ({:.6f} to {:.6f} m over {} records)",
                    geometry.offset_forward_m, m.min_forward_m, m.max_forward_m, m.samples);
  else
    mount = fmt::format("laser {:.4f} m ahead ({})", geometry.offset_forward_m,
                        trace.format() == "rowild" ? "the Wean robot's; RoWild lines carry no laser pose"
                                                   : "from the file's sensor pose");
  out << "trace: " << path << " (" << trace.format() << ", " << trace.size() << " laser records, "
      << geometry.beam_count << " beams; " << mount << ")\n";
  const TimeGlitchStats& g = stats.time_glitches;
  if (g.count > 0) {
    warnings << fmt::format(
        "rcbench: warning: {}: {} laser record(s) step back in time by less than {:.1f} s (largest {:.6f} s, first on "
        "line {}); kept as logged: a clock glitch, and the motion model uses poses, not times\n",
        path, g.count, kMaxClockGlitchS, g.largest_step_s, g.first_line);
  }
}

}  // namespace rc
