#include "backends/modelled_backend.h"

namespace rc {

BackendSpecs ModelledBackendSpecs(const std::string& name, const std::string& description, const GpuParams& gpu) {
  BackendSpecs specs;
  specs.name = name;
  specs.description = description;
  specs.has_cost_model = true;
  specs.step_programs = {StepProgramKind::kGridMarch,     StepProgramKind::kDdaStep,
                         StepProgramKind::kRmStep,        StepProgramKind::kSactTest,
                         StepProgramKind::kBallQueryPRay, StepProgramKind::kBallQueryPSphere};
  specs.clock_hz = gpu.core_clock_hz;
  specs.sms = gpu.sms;
  return specs;
}

BatchCost ModelledBatchCost(const std::string& name, const KernelRecord& record, const GpuParams& gpu,
                            const MemoryProfile& memory) {
  BatchCost cost;
  cost.backend = name;
  cost.modelled = true;
  cost.queries = record.query_count();
  cost.nodes = record.total_nodes();
  cost.clock_hz = gpu.core_clock_hz;
  cost.memory = memory.totals;
  cost.l1_model = memory.l1_model;
  cost.l2_model = memory.l2_model;
  return cost;
}

void FinishKernelCycles(BatchCost& cost, std::uint64_t launch_cycles, std::uint64_t busiest_sm_cycles,
                        const GpuParams& gpu) {
  const auto dram_cycles = static_cast<std::uint64_t>(static_cast<double>(cost.memory.dram_accesses) *
                                                      gpu.sector_bytes / gpu.DramBytesPerCoreCycle());
  std::uint64_t busiest = busiest_sm_cycles;
  if (dram_cycles > busiest) {
    busiest = dram_cycles;
    cost.bound = "DRAM bandwidth";
  }
  cost.launch_cycles = launch_cycles;
  cost.cycles = launch_cycles + busiest;
  cost.seconds = static_cast<double>(cost.cycles) / gpu.core_clock_hz;
}

}  // namespace rc
