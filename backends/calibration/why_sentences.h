#pragma once
// The "why ours differs" column, computed from the run: what limited each
// side's busiest SM (BatchCost::bound), what its counters say (warp
// instructions and SIMT efficiency, micro-ops and hops, sector requests and
// hits, the launch's share of the time), and nothing else. Each clause is
// chosen by the kind of bound measured, so a parameter change that moves a
// side from one bound to another changes the sentence
// (tests/calibration/why_sentences_test.cc).
//
//   SideEvidence robo("RoboCore");  robo.Add(cost);   // one or more launches
//   std::string why = CompareSides(robo, simt);       // "RoboCore ...; the CUDA cores ..."
#include <map>
#include <string>

#include "backends/backend.h"

namespace rc {

// The kinds of bound the backends report (backend.h, BatchCost::bound):
// SIMT: "latency (resident warps)", "issue", "<class> pipe", "L1 bandwidth";
// RT units: "latency (warp buffer)", "op unit <UNIT>", "L1 requests",
// "thread intake"; both: "DRAM bandwidth".
enum class BoundKind : std::uint8_t { kLatency, kIssue, kPipe, kL1, kDram, kOpUnit, kThreadIntake };
// Throws std::logic_error for a bound text no backend writes.
BoundKind ClassifyBound(const std::string& bound);
const char* ToString(BoundKind kind);  // "latency", "issue", "pipe", "L1", "DRAM", "OP unit", "thread intake"

// A side's costs summed over one or more launches (a batch, a whole run,
// several scenes) and the bound that held for most of its kernel cycles.
class SideEvidence {
 public:
  explicit SideEvidence(std::string label) : label_(std::move(label)) {}
  void Add(const BatchCost& cost);
  void Add(const SideEvidence& more);  // the same label's launches elsewhere

  const std::string& label() const { return label_; }  // "RoboCore", "the CUDA cores", ...
  bool empty() const { return launches_ == 0; }
  bool simt() const { return simt_; }
  long launches() const { return launches_; }
  // The bound of the most kernel cycles, and that share of the kernel cycles.
  const std::string& bound() const { return bound_; }
  BoundKind bound_kind() const { return ClassifyBound(bound_); }
  double bound_share() const;
  double seconds() const { return total_.seconds; }
  double kernel_seconds() const;  // without the launches
  double launch_share() const;    // launch cycles / cycles
  const BatchCost& total() const { return total_; }
  double simt_efficiency() const;  // SIMT: thread / (warp size x warp instructions)
  double micro_ops() const;        // RT units: executed, LOAD excluded
  double l1_hit_rate() const;

 private:
  void PickBound();
  std::string label_;
  BatchCost total_;
  long launches_ = 0;
  bool simt_ = false;
  std::map<std::string, double> kernel_cycles_by_bound_;
  std::string bound_;
};

// Reporting rule (not a cost parameter): a fixed cost worth naming in a
// sentence is at least this share of a side's time; below it, a launch
// moves a ratio by less than this fraction. Unit: fraction of the side's
// cycles; range (0, 1); source: this report's choice of what to mention.
inline constexpr double kLaunchShareWorthNaming = 0.10;

// What limits one side, with the counters that show it, e.g. "the CUDA
// cores' busiest SM is issue-bound (1.2e+06 warp instructions at 64% of
// lanes active)". Chosen by bound_kind().
std::string BoundClause(const SideEvidence& side);
// "<a's clause>; <b's clause>", plus each side's launch share when it is
// worth naming.
std::string CompareSides(const SideEvidence& a, const SideEvidence& b);
// A short "what limits it" tag, e.g. "RoboCore: latency (warp buffer)", for
// telling whether another preset's run was limited by something else.
std::string LimitTag(const SideEvidence& side);

}  // namespace rc
