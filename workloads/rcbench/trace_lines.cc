#include "workloads/rcbench/trace_lines.h"

#include <cstdio>

#include "traces/record_fields.h"

namespace rc {

void PrintTraceLines(std::ostream& out, std::ostream& warnings, const ScanSource& trace,
                     const TraceReadStats& stats, bool mount_given) {
  const std::string& path = trace.source_path();
  const LaserGeometry& geometry = trace.geometry();
  char mount[200];
  const LaserMountStats& m = stats.laser_mount;
  if (mount_given)
    std::snprintf(mount, sizeof mount, "laser %.4f m ahead (--laser-offset)", geometry.offset_forward_m);
  else if (m.samples > 0)
    std::snprintf(mount, sizeof mount,
                  "laser %.4f m ahead, measured from the file's laser poses (%.6f to %.6f m over %ld records)",
                  geometry.offset_forward_m, m.min_forward_m, m.max_forward_m, m.samples);
  else
    std::snprintf(mount, sizeof mount, "laser %.4f m ahead (%s)", geometry.offset_forward_m,
                  trace.format() == "rowild" ? "the Wean robot's; RoWild lines carry no laser pose"
                                           : "from the file's sensor pose");
  out << "trace: " << path << " (" << trace.format() << ", " << trace.size() << " laser records, "
      << geometry.beam_count << " beams; " << mount << ")\n";
  const TimeGlitchStats& g = stats.time_glitches;
  if (g.count > 0) {
    char text[300];
    std::snprintf(text, sizeof text,
                  "rcbench: warning: %s: %ld laser record(s) step back in time by less than %.1f s (largest "
                  "%.6f s, first on line %ld); kept as logged: a clock glitch, and the motion model uses poses, "
                  "not times\n",
                  path.c_str(), g.count, kMaxClockGlitchS, g.largest_step_s, g.first_line);
    warnings << text;
  }
}

}  // namespace rc
