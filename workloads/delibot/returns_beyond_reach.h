#pragma once
// How far the sensor models reach (--max-range), fitted to the trace: a
// return (a reading below the sensor's own max range,
// LaserGeometry::max_range_m) at or beyond the models' max range counts as
// "no return". In a building whose walls are farther than the default
// 10 m (the generated 60 m hall), most scans would then say little, and
// global localization fails for that reason alone. So when more than a
// quarter of a trace's returns lie beyond the default reach and the user
// did not set --max-range, the reach widens to cover 95 % of them; the
// traces every check of the defaults ran on have at most 8 % beyond 10 m,
// so there it stays 10 m (docs/delibot.md, "Max range").
#include <string>
#include <vector>

#include "traces/scan_source.h"

namespace rc {

// Share of a trace's returns beyond the models' reach above which the reach
// widens (--max-range not given) or `rcbench delibot` notes it (given).
// Unit: fraction, [0, 1]. Source: measured with the default 10 m reach: the
// four Wean logs and the held-out robotdata5 3-6 %, a simulated Intel lab
// trace 8 %, the demo and the MovingAI traces of the claim audit's checks
// (at 0.05 m cells) 0-1 %; the generated hall 40 %.
inline constexpr double kBeyondReachFraction = 0.25;
// The share of the returns a widened reach covers. Unit: fraction, (0, 1].
// Source: what the default 10 m covers on the Wean logs the defaults were
// chosen on (their 95th percentile returns are 9.7-10.5 m).
inline constexpr double kWidenedReachQuantile = 0.95;
// Return-length bins per metre (0.1 m bins) the quantile is read from; a
// widened reach is a bin's upper edge. Source: the Wean map's 0.1 m cell.
inline constexpr int kReachBinsPerM = 10;

struct ReturnsBeyondReach {
  long returns = 0;        // readings below the sensor's max range
  long beyond = 0;         // of those, at or beyond the models' max range
  double longest_m = 0.0;  // the longest return (m)
  std::vector<long> bins;  // returns per 1 / kReachBinsPerM m of length, from 0
  double Fraction() const { return returns > 0 ? static_cast<double>(beyond) / returns : 0.0; }
  // The smallest bin edge (m) that at least `q` of the returns lie below.
  double QuantileM(double q) const;
};

// Reads every record of `scans` (every beam) and rewinds it.
ReturnsBeyondReach CountReturnsBeyondReach(ScanSource& scans, double model_max_range_m);

// Fits the models' reach to the trace: with --max-range not given and more
// than kBeyondReachFraction of the returns beyond `max_range_m`, widens
// it to the kWidenedReachQuantile return. Returns the note for the user
// (one line ending in a newline: the reach widened, or, given, that many
// returns lie beyond it), or "" when at most that share lies beyond.
std::string FitReachToTrace(double& max_range_m, const ReturnsBeyondReach& count, bool max_range_given);

}  // namespace rc
