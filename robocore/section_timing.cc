#include "robocore/section_timing.h"

#include <stdexcept>

namespace rc {
namespace {

// Position of a SACT unit in the Pre-Process -> Box-Normal -> Edge x Edge
// chain; -1 for any other unit.
int ChainPosition(OpUnit unit) {
  switch (unit) {
    case OpUnit::kPreProcess: return 0;
    case OpUnit::kBoxNormal: return 1;
    case OpUnit::kEdgeEdge: return 2;
    default: return -1;
  }
}

LoweredOp Lower(Opcode opcode, int width, int line, const DatapathConfig& config) {
  const OpcodeInfo& info = InfoOf(opcode);
  LoweredOp op;
  op.opcode = opcode;
  op.width = static_cast<std::uint8_t>(width);
  op.unit = info.unit;
  op.latency = LatencyOf(info.unit, config.latencies);
  op.initiation = info.unit == OpUnit::kRcp ? config.latencies.rcp_initiation_cycles : 1;
  if (info.sact) {  // RoboCore's pipelined SACT units (PRE, BOX, EDGE)
    if (info.unit == OpUnit::kPreProcess) op.initiation = config.pre_process_initiation_cycles;
    if (info.unit == OpUnit::kBoxNormal) op.initiation = config.box_normal_initiation_cycles;
    if (info.unit == OpUnit::kEdgeEdge) op.initiation = config.edge_edge_initiation_cycles;
  }
  op.source_line = line;
  return op;
}

SectionCost Summarize(const std::vector<PlannedOp>& plan, const DatapathConfig& config);

}  // namespace

int LatencyOf(OpUnit unit, const OpUnitLatencies& l) {
  switch (unit) {
    case OpUnit::kAddSub: return l.addsub_cycles;
    case OpUnit::kMinMax: return l.minmax_cycles;
    case OpUnit::kMaxMin: return l.maxmin_cycles;
    case OpUnit::kCmp: return l.cmp_cycles;
    case OpUnit::kMul: return l.mul_cycles;
    case OpUnit::kRcp: return l.rcp_cycles;
    case OpUnit::kPreProcess: return l.pre_process_cycles;
    case OpUnit::kBoxNormal: return l.box_normal_cycles;
    case OpUnit::kEdgeEdge: return l.edge_edge_cycles;
    case OpUnit::kLogic: return l.logic_cycles;
    case OpUnit::kPush: return l.push_cycles;
    case OpUnit::kReturn: return l.return_cycles;
    case OpUnit::kFetch: return 0;
  }
  return 0;
}

const char* ToString(EarlyExitMode mode) {
  switch (mode) {
    case EarlyExitMode::kNone: return "none";
    case EarlyExitMode::kPredication: return "predication";
    case EarlyExitMode::kConditionalReturn: return "conditional-return";
  }
  return "?";
}

void Accumulate(SectionCost& into, const SectionCost& add) {
  into.cycles += add.cycles;
  into.hops += add.hops;
  into.predicated_off += add.predicated_off;
  into.ctrl_exits += add.ctrl_exits;
  for (int i = 0; i < kOpcodeCount; ++i) into.executed[i] += add.executed[i];
  for (int i = 0; i < kOpUnitCount; ++i) into.unit_slots[i] += add.unit_slots[i];
  into.arithmetic += add.arithmetic;
  into.loads += add.loads;
  into.pushes += add.pushes;
}

SectionTiming::SectionTiming(const std::vector<MicroOp>& source, const DatapathConfig& config) : config_(config) {
  const bool robocore = config.kind == DatapathKind::kRoboCore;
  int returns = 0;
  for (std::size_t i = 0; i < source.size(); ++i) {
    const MicroOp& op = source[i];
    const OpcodeInfo& info = InfoOf(op.opcode);
    if (op.opcode == Opcode::kReturnIf) {
      LoweredOp r = Lower(op.opcode, 1, static_cast<int>(op.line), config);
      r.return_index = returns++;
      r.dropped = config.exit_mode == EarlyExitMode::kNone;
      // CTRL folds the exit test of the axis a SACT unit has just computed.
      const MicroOp* prev = i > 0 ? &source[i - 1] : nullptr;
      r.ctrl_exit = robocore && !r.dropped && prev && InfoOf(prev->opcode).sact && !prev->operands.empty() &&
                    prev->operands[0] == op.operands[0];
      ops_.push_back(r);
      continue;
    }
    if (info.sact && !robocore) {
      for (const ExpandedOp& e : TtaPlusExpansion(op.opcode))
        ops_.push_back(Lower(e.opcode, e.width, static_cast<int>(op.line), config));
      continue;
    }
    ops_.push_back(Lower(op.opcode, op.width, static_cast<int>(op.line), config));
  }
  if (robocore) {
    // A SACT micro-op reaches its unit over the chain when the previous
    // micro-op that ran on a unit was a SACT micro-op on the same unit (CTRL
    // loops the query back for the next axis) or on an earlier unit.
    int prev_position = -1;
    for (LoweredOp& op : ops_) {
      if (op.dropped || op.ctrl_exit) continue;
      const int position = InfoOf(op.opcode).sact ? ChainPosition(op.unit) : -1;
      op.chained = position >= 0 && prev_position >= 0 && prev_position <= position;
      prev_position = position;
    }
  }
  if (returns >= kNoExit) throw std::invalid_argument("a section may hold at most 254 RETURN_IFs");
  costs_.assign(1 + returns, SectionCost{});
  costs_[0] = Summarize(Plan(kNoExit), config);
  for (int j = 0; j < returns; ++j) costs_[1 + j] = Summarize(Plan(static_cast<std::uint8_t>(j)), config);
}

std::vector<PlannedOp> SectionTiming::Plan(std::uint8_t exit) const {
  const int fired_return = exit == kNoExit ? -1 : exit;
  std::vector<PlannedOp> plan;
  bool fired = false;
  bool have_prev = false;
  OpUnit prev = OpUnit::kFetch;
  auto step = [&](const LoweredOp& op) {
    PlannedOp p;
    p.opcode = op.opcode;
    p.width = op.width;
    p.unit = op.unit;
    p.latency = op.latency;
    p.initiation = op.initiation;
    p.chained = op.chained;
    p.hop_before = have_prev && op.unit != prev && !op.chained;
    prev = op.unit;
    have_prev = true;
    return p;
  };
  for (const LoweredOp& op : ops_) {
    if (op.dropped) continue;
    if (fired) {
      if (config_.exit_mode == EarlyExitMode::kConditionalReturn) break;
      if (op.ctrl_exit) continue;
      // Predication: the micro-op still travels to its unit and takes a slot.
      PlannedOp p = step(op);
      p.latency = config_.predicated_op_cycles;
      p.initiation = config_.predicated_op_cycles;
      p.predicated = true;
      plan.push_back(p);
      continue;
    }
    if (op.unit == OpUnit::kFetch) {  // the node fetch; the caches price its latency
      PlannedOp p;
      p.opcode = op.opcode;
      p.unit = op.unit;
      p.load = true;
      plan.push_back(p);
      have_prev = false;
      continue;
    }
    if (op.ctrl_exit) {
      PlannedOp p;
      p.opcode = op.opcode;
      p.unit = prev;
      p.ctrl = true;
      p.fires = fired = op.return_index == fired_return;
      // Only the check that fires costs cycles: the artifact appends one
      // RETURN op after the separating axis and none after the others
      // (docs/artifact_preset.md, "Values read from the artifact's code").
      p.latency = p.fires ? config_.ctrl_exit_cycles : 0;
      plan.push_back(p);
      continue;
    }
    PlannedOp p = step(op);
    p.fires = fired = op.return_index >= 0 && op.return_index == fired_return;
    plan.push_back(p);
  }
  return plan;
}

namespace {

SectionCost Summarize(const std::vector<PlannedOp>& plan, const DatapathConfig& config) {
  SectionCost c;
  for (const PlannedOp& p : plan) {
    if (p.load) {
      ++c.loads;
      ++c.executed[static_cast<int>(p.opcode)];
      continue;
    }
    if (p.ctrl) {
      c.cycles += p.latency;
      ++c.ctrl_exits;
      continue;
    }
    if (p.hop_before) {
      c.cycles += config.interconnect_hop_cycles;
      ++c.hops;
    }
    c.cycles += p.latency;
    c.unit_slots[static_cast<int>(p.unit)] += p.initiation;
    if (p.predicated) {
      ++c.predicated_off;
      continue;
    }
    ++c.executed[static_cast<int>(p.opcode)];
    c.arithmetic += ContentOf(p.opcode, p.width);
    if (p.opcode == Opcode::kPush) ++c.pushes;
  }
  return c;
}

}  // namespace

ProgramTiming::ProgramTiming(const MicroProgram& program, const MicroProgram* leaf_program,
                             const DatapathConfig& config)
    : prologue(program.section(ProgramSection::kPrologue), config),
      loop(program.section(ProgramSection::kLoop), config),
      epilogue(program.section(ProgramSection::kEpilogue), config) {
  if (leaf_program) {
    if (!leaf_program->section(ProgramSection::kPrologue).empty() || leaf_program->has_loop())
      throw std::invalid_argument("leaf program '" + leaf_program->name() + "' must hold only an epilogue: section");
    leaf = SectionTiming(leaf_program->section(ProgramSection::kEpilogue), config);
  }
  once_ = prologue.Cost(kNoExit);
  Accumulate(once_, epilogue.Cost(kNoExit));
  Accumulate(once_, leaf.Cost(kNoExit));
}

}  // namespace rc
