#pragma once
// How much of a trace's evidence the sensor models cannot use: a return (a
// reading below the sensor's own max range, LaserGeometry::max_range_m) at
// or beyond the models' max range (--max-range) counts as "no return". In a
// building whose walls are farther than that reach (the generated 60 m
// hall), most scans then say little, and global localization can fail for
// that reason alone; `rcbench delibot` notes it, computed from the trace.
#include <string>

#include "traces/scan_source.h"

namespace rc {

// Share of a trace's returns beyond the models' reach above which `rcbench
// delibot` prints a note ([0, 1]). Measured, with the default 10 m reach:
// the four Wean logs 3-6 %, the demo 1 %, a simulated Intel lab trace 8 %;
// the generated hall 40 %, the MovingAI 64room_005 and maze512-32-9 traces
// of the claim audit's checks 70 % and 97 % (docs/delibot.md, "Max range").
// The note changes nothing in the run.
inline constexpr double kBeyondReachNoteFraction = 0.25;

struct ReturnsBeyondReach {
  long returns = 0;        // readings below the sensor's max range
  long beyond = 0;         // of those, at or beyond the models' max range
  double longest_m = 0.0;  // the longest return (m)
  double Fraction() const { return returns > 0 ? static_cast<double>(beyond) / returns : 0.0; }
};

// Reads every record of `scans` (every beam) and rewinds it.
ReturnsBeyondReach CountReturnsBeyondReach(ScanSource& scans, double model_max_range_m);

// The note for the user (one line, ending in a newline), or "" when at most
// kBeyondReachNoteFraction of the returns lie beyond the reach.
std::string BeyondReachNote(const ReturnsBeyondReach& count, double model_max_range_m);

}  // namespace rc
