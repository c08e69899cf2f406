#include "backends/calibration/why_sentences.h"

#include <stdexcept>

#include <fmt/format.h>

#include "backends/calibration/calibration_row.h"

namespace rc {
namespace {

bool StartsWith(const std::string& text, const char* prefix) { return text.rfind(prefix, 0) == 0; }

// "op unit BOX_NORMAL" -> "Box-Normal"-style name a reader knows.
std::string UnitName(const std::string& bound) {
  const std::string unit = bound.substr(std::string("op unit ").size());
  if (unit == "PRE_PROCESS") return "Pre-Process (SACT)";
  if (unit == "BOX_NORMAL") return "Box-Normal (SACT, DOT)";
  if (unit == "EDGE_EDGE") return "Edge x Edge (SACT, CROSS)";
  return unit;
}

// "RoboCore's", "the CUDA cores'"; "is" / "are".
std::string Possessive(const std::string& who) { return who + (who.back() == 's' ? "'" : "'s"); }
const char* Is(const std::string& who) { return who.back() == 's' ? "are" : "is"; }

std::string Share(const SideEvidence& side) {
  if (side.launches() <= 1 || side.bound_share() >= 0.995) return "";
  return fmt::format(" for {:.0f}% of its kernel cycles", 100.0 * side.bound_share());
}

}  // namespace

BoundKind ClassifyBound(const std::string& bound) {
  if (StartsWith(bound, "latency")) return BoundKind::kLatency;
  if (bound == "issue") return BoundKind::kIssue;
  if (bound.size() > 5 && bound.compare(bound.size() - 5, 5, " pipe") == 0) return BoundKind::kPipe;
  if (bound == "L1 bandwidth" || bound == "L1 requests") return BoundKind::kL1;
  if (bound == "DRAM bandwidth") return BoundKind::kDram;
  if (StartsWith(bound, "op unit ")) return BoundKind::kOpUnit;
  if (bound == "thread intake") return BoundKind::kThreadIntake;
  throw std::logic_error("why sentences: no backend reports the bound '" + bound + "'");
}

const char* ToString(BoundKind kind) {
  switch (kind) {
    case BoundKind::kLatency: return "latency";
    case BoundKind::kIssue: return "issue";
    case BoundKind::kPipe: return "pipe";
    case BoundKind::kL1: return "L1";
    case BoundKind::kDram: return "DRAM";
    case BoundKind::kOpUnit: return "OP unit";
    case BoundKind::kThreadIntake: return "thread intake";
  }
  return "?";
}

void SideEvidence::Add(const BatchCost& cost) {
  if (launches_ == 0) {
    total_ = cost;
    simt_ = !std::isnan(cost.simt_efficiency);
  } else {
    total_ += cost;
  }
  ++launches_;
  kernel_cycles_by_bound_[cost.bound] += static_cast<double>(cost.cycles - cost.launch_cycles);
  PickBound();
}

void SideEvidence::Add(const SideEvidence& more) {
  if (more.empty()) return;
  if (empty()) {
    const std::string label = label_;
    *this = more;
    label_ = label;
    return;
  }
  total_ += more.total_;
  launches_ += more.launches_;
  for (const auto& [bound, cycles] : more.kernel_cycles_by_bound_) kernel_cycles_by_bound_[bound] += cycles;
  PickBound();
}

void SideEvidence::PickBound() {
  double most = -1;
  for (const auto& [bound, cycles] : kernel_cycles_by_bound_)
    if (cycles > most) most = cycles, bound_ = bound;
}

double SideEvidence::bound_share() const {
  double all = 0;
  for (const auto& entry : kernel_cycles_by_bound_) all += entry.second;
  return all > 0 ? kernel_cycles_by_bound_.at(bound_) / all : 1.0;
}

double SideEvidence::kernel_seconds() const {
  return static_cast<double>(total_.cycles - total_.launch_cycles) / total_.clock_hz;
}

double SideEvidence::launch_share() const {
  return total_.cycles ? static_cast<double>(total_.launch_cycles) / static_cast<double>(total_.cycles) : 0.0;
}

double SideEvidence::simt_efficiency() const {
  return total_.warp_instructions
             ? static_cast<double>(total_.thread_instructions) / (32.0 * static_cast<double>(total_.warp_instructions))
             : 1.0;
}

double SideEvidence::micro_ops() const {
  double n = 0;
  for (int i = 0; i < kOpcodeCount; ++i)
    if (static_cast<Opcode>(i) != Opcode::kLoad) n += static_cast<double>(total_.micro_ops[i]);
  return n;
}

double SideEvidence::l1_hit_rate() const {
  return total_.memory.sector_requests
             ? static_cast<double>(total_.memory.l1_hits) / static_cast<double>(total_.memory.sector_requests)
             : 0.0;
}

std::string BoundClause(const SideEvidence& side) {
  const std::string& who = side.label();
  const BoundKind kind = side.bound_kind();
  const std::string share = Share(side);
  switch (kind) {
    case BoundKind::kLatency:
      if (side.simt())
        return fmt::format(
            "{} {} latency-bound{}: the resident warps' dependent chains (instruction latencies and the "
            "slowest lane's fetches) set the time, not issue ({:.3g} warp instructions, SIMT efficiency {:.2f})",
            who.c_str(), Is(who), share.c_str(), double(side.total().warp_instructions), side.simt_efficiency());
      return fmt::format(
          "{} {} latency-bound{}: each query's chain of micro-op latencies and node fetches ({:.3g} micro-ops, "
          "{:.0f}% L1 hits) passes through the warp buffer, which no other bound outlasts",
          who.c_str(), Is(who), share.c_str(), side.micro_ops(), 100.0 * side.l1_hit_rate());
    case BoundKind::kIssue:
      return fmt::format(
          "{} busiest SM is issue-bound{}: {:.3g} warp instructions at one per scheduler per "
          "cycle, with {:.0f}% of lanes active (SIMT efficiency {:.2f})",
          Possessive(who).c_str(), share.c_str(), double(side.total().warp_instructions),
          100.0 * side.simt_efficiency(), side.simt_efficiency());
    case BoundKind::kPipe:
      return fmt::format(
          "{} busiest SM is bound by its {}{} ({:.3g} warp instructions; a class's initiation "
          "interval holds the pipe{})",
          Possessive(who).c_str(), side.bound().c_str(), share.c_str(), double(side.total().warp_instructions),
          side.bound() == "SFU pipe" ? ", and FP64 and divisions issue to the SFU pipe" : "");
    case BoundKind::kL1:
      return fmt::format(
          "{} {} bound by L1 bandwidth{}: {:.3g} sector requests ({:.0f}% hits) at a fixed number "
          "per cycle",
          who.c_str(), Is(who), share.c_str(), double(side.total().memory.sector_requests), 100.0 * side.l1_hit_rate());
    case BoundKind::kDram:
      return fmt::format("{} {} bound by DRAM bandwidth{}: {:.3g} DRAM sector accesses", who.c_str(), Is(who),
                         share.c_str(), double(side.total().memory.dram_accesses));
    case BoundKind::kOpUnit:
      return fmt::format(
          "{} busiest unit is its {} OP unit{}: one per intersection unit set, taking a "
          "micro-op per initiation interval ({:.3g} micro-ops, {:.3g} interconnect hops)",
          Possessive(who).c_str(), UnitName(side.bound()).c_str(), share.c_str(), side.micro_ops(),
          double(side.total().interconnect_hops));
    case BoundKind::kThreadIntake:
      return fmt::format(
          "{} {} bound by thread intake{}: the unit sets take a few threads per cycle and each "
          "query does little work ({:.3g} micro-ops for {:.3g} queries)",
          who.c_str(), Is(who), share.c_str(), side.micro_ops(), double(side.total().queries));
  }
  return "";
}

std::string CompareSides(const SideEvidence& a, const SideEvidence& b) {
  std::string text = BoundClause(a) + "; " + BoundClause(b);
  for (const SideEvidence* side : {&a, &b})
    if (side->launch_share() >= kLaunchShareWorthNaming)
      text += fmt::format("; the launch is {:.0f}% of {} time", 100.0 * side->launch_share(),
                          Possessive(side->label()).c_str());
  return text + ".";
}

std::string LimitTag(const SideEvidence& side) { return side.label() + ": " + side.bound(); }

}  // namespace rc
