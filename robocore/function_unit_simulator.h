#pragma once
// A cycle-level model of one intersection unit set ("function unit") of a
// RoboCore / TTA+ unit: one OP unit per unit type, each a pipeline with a
// latency and an initiation interval, an interconnect between them, and the
// SACT chain with its CTRL block and input arbiter.
//
// Every thread runs one execution of a section (for example one node's SACT
// test) given the RETURN_IF that fires for it. Per cycle:
//   - up to `threads_accepted_per_cycle` threads enter from the thread queue
//     and go straight to the unit of their first micro-op (artifact: 2 per
//     cycle per function unit, -gpgpu_rt_func_bw);
//   - each unit whose initiation interval has passed takes one waiting
//     packet. The input arbiter serves packets arriving over the SACT chain
//     (or looping back for the next axis) before packets from the
//     interconnect or the thread queue (paper: "chained SACT packets have
//     priority over packets from the interconnect"); ties go to the earliest
//     arrival, then the lowest thread;
//   - a finished micro-op sends its thread to the next one: the same unit
//     directly, the next SACT unit over the chain, or any other unit over the
//     interconnect (one hop). CTRL checks a SACT result as it leaves the unit
//     and ends the thread at a separating axis; it also counts the axes each
//     thread has tested.
// A node fetch (LOAD) takes the thread's given memory latency.
//
// The batch pricing uses the analytic section costs (section_timing.h) and
// a first-order unit model; this simulator is their reference on small
// cases: alone, a thread's latency equals its analytic section cost, and
// under contention it shows queueing and the arbiter at work.
#include <array>
#include <cstdint>
#include <vector>

#include "robocore/section_timing.h"

namespace rc {

struct SimulatedThread {
  std::uint8_t exit = kNoExit;  // RETURN_IF that fires in this execution
  int load_latency_cycles = 0;  // latency of its node fetch, if the section has one
};

struct SimulatedThreadResult {
  std::uint64_t finish_cycle = 0;  // cycle its last micro-op completes
  int axes_tested = 0;             // CTRL's axis counter (BOX + EDGE completed)
  bool exited_early = false;       // a RETURN_IF or CTRL check fired
};

struct FunctionUnitSimulation {
  std::vector<SimulatedThreadResult> threads;
  std::uint64_t cycles = 0;               // until the last thread finished
  std::uint64_t chain_priority_wins = 0;  // cycles a chained packet was served while
                                          // an interconnect packet also waited
  std::uint64_t hops = 0;
  std::array<std::uint64_t, kOpUnitCount> busy_cycles{};  // input slots used per unit
};

FunctionUnitSimulation SimulateFunctionUnit(const SectionTiming& section, const std::vector<SimulatedThread>& threads,
                                            int threads_accepted_per_cycle);

}  // namespace rc
