#pragma once
// Small helpers the calibration rows share: pricing one record on named
// backends under given parameters, and reading times and counts out of the
// resulting BatchCosts.
#include <map>
#include <string>
#include <vector>

#include "backends/backend.h"

namespace rc {

// Prices `record` on each named backend (sharing the memory replay);
// returns the costs by name.
std::map<std::string, BatchCost> PriceByName(const std::vector<std::string>& names, const KernelRecord& record,
                                             const BackendParameters& params);

// Modelled seconds without the kernel launch: what the queries themselves
// cost (the launch is a fixed 5000+ cycles that a small batch cannot hide).
double KernelSeconds(const BatchCost& cost);

// Micro-ops executed (all kinds but LOAD).
std::uint64_t MicroOpsExecuted(const BatchCost& cost);

// Average computation latency per query, cycles: the once-per-query
// sections plus every node's loop pass with the exit the record gives, on
// `datapath` (the section tables the RT-unit backends price with; node
// fetch latency excluded).
double AverageComputationCycles(const KernelRecord& record, const DatapathConfig& datapath);

// Loop micro-ops of the record's step program (LOAD and RETURN_IF markers
// excluded), and how many of them are CMP.
struct LoopMix {
  int micro_ops = 0;
  int compares = 0;
};
LoopMix LoopMixOf(const MicroProgram& program);

}  // namespace rc
