#pragma once
// Timing of one program section on a RoboCore / TTA+ datapath: the section
// is lowered to the micro-ops that datapath runs (SACT expansions on TTA+,
// CTRL-folded returns on RoboCore), then walked once per possible exit to
// give the latency, interconnect hops, predicated-off slots, unit issue
// slots and arithmetic of one execution. Pricing a batch then costs one
// table lookup per node.
//
// One thread's micro-ops run one after another, each waiting for the
// previous (the artifact replays each thread's op sequence the same way).
// Node-fetch (LOAD) latency is not included: it depends on the caches and
// is added by the backend. A LOAD also breaks the interconnect chain: a
// thread re-enters the units from the fetch path without a hop, as in the
// artifact, where a transaction's first op is dispatched from the thread
// queue.
#include <array>
#include <cstdint>
#include <vector>

#include "robocore/datapath_params.h"
#include "robocore/micro_program.h"

namespace rc {

// "No RETURN_IF fired in this execution."
inline constexpr std::uint8_t kNoExit = 0xFF;

struct LoweredOp {
  Opcode opcode = Opcode::kAdd;  // what runs on the datapath
  std::uint8_t width = 1;
  OpUnit unit = OpUnit::kAddSub;
  int latency = 0;
  int initiation = 1;      // cycles the micro-op holds its unit's input
  int return_index = -1;   // RETURN_IF ordinal within the section, else -1
  bool ctrl_exit = false;  // RoboCore: a RETURN_IF folded into CTRL
  bool chained = false;    // RoboCore: reaches its SACT unit over the chain
  bool dropped = false;    // plain TTA+: a RETURN_IF marker, not run
  int source_line = 0;
};

// One step of one execution, in order: what a thread actually does once the
// exit is known. The analytic cost sums these; the cycle-level simulator
// (function_unit_simulator.h) replays them through shared units.
struct PlannedOp {
  Opcode opcode = Opcode::kAdd;
  std::uint8_t width = 1;
  OpUnit unit = OpUnit::kAddSub;
  int latency = 0;          // cycles in the unit (CTRL: its decision cycles)
  int initiation = 1;       // cycles the unit's input is held
  bool hop_before = false;  // crosses the interconnect to reach `unit`
  bool chained = false;     // arrives over the SACT chain (arbiter priority)
  bool predicated = false;  // travels without doing work (predication)
  bool ctrl = false;        // a CTRL-folded RETURN_IF: no unit, no hop
  bool load = false;        // the node fetch
  bool fires = false;       // this RETURN_IF (or CTRL check) is the one that fired
};

struct SectionCost {
  std::uint32_t cycles = 0;                              // latency of one execution, LOAD excluded
  std::uint32_t hops = 0;                                // interconnect hops taken
  std::uint32_t predicated_off = 0;                      // micro-ops that travelled without work
  std::uint32_t ctrl_exits = 0;                          // CTRL-folded RETURN_IFs evaluated
  std::array<std::uint32_t, kOpcodeCount> executed{};    // micro-ops that did work
  std::array<std::uint32_t, kOpUnitCount> unit_slots{};  // issue cycles held per unit
  ArithmeticContent arithmetic;
  std::uint32_t loads = 0;
  std::uint32_t pushes = 0;
};

class SectionTiming {
 public:
  SectionTiming() = default;
  SectionTiming(const std::vector<MicroOp>& ops, const DatapathConfig& config);

  const std::vector<LoweredOp>& ops() const { return ops_; }
  int return_count() const { return static_cast<int>(costs_.size()) - 1; }
  // One execution in which RETURN_IF #exit fired; kNoExit: none fired.
  const SectionCost& Cost(std::uint8_t exit) const { return costs_[exit == kNoExit ? 0 : 1 + exit]; }
  // The steps of one execution in which RETURN_IF #exit fired.
  std::vector<PlannedOp> Plan(std::uint8_t exit) const;
  const DatapathConfig& config() const { return config_; }

 private:
  DatapathConfig config_;
  std::vector<LoweredOp> ops_;
  std::vector<SectionCost> costs_{SectionCost{}};  // [0] no exit, [1 + j] exit at j
};

// A step program (prologue, loop, epilogue) plus an optional leaf that runs
// once per query after the epilogue.
struct ProgramTiming {
  SectionTiming prologue;
  SectionTiming loop;
  SectionTiming epilogue;
  SectionTiming leaf;
  ProgramTiming() = default;
  ProgramTiming(const MicroProgram& program, const MicroProgram* leaf_program, const DatapathConfig& config);
  // Cost of everything a query runs once (prologue + epilogue + leaf).
  const SectionCost& once() const { return once_; }

 private:
  SectionCost once_;
};

void Accumulate(SectionCost& into, const SectionCost& add);

}  // namespace rc
