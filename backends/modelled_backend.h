#pragma once
// What every modelled backend (simt, ttaplus, ttaplus-p, ttaplus-cr,
// robocore) fills the same way: its specs (a cost model, the kernels it
// prices, the clock its cycles count, its SMs) and the frame of its
// BatchCost (the record's counts, the memory replay's results, the kernel's
// time from its busiest SM and the DRAM bandwidth).
#include <cstdint>
#include <string>

#include "backends/backend.h"

namespace rc {

inline std::uint64_t CeilDiv(std::uint64_t a, std::uint64_t b) { return (a + b - 1) / b; }

// The step programs are one list: a new kernel is priced by every modelled
// backend or by none.
BackendSpecs ModelledBackendSpecs(const std::string& name, const std::string& description, const GpuParams& gpu);

// A BatchCost holding the record's counts and the memory replay's results.
BatchCost ModelledBatchCost(const std::string& name, const KernelRecord& record, const GpuParams& gpu,
                            const MemoryProfile& memory);

// The kernel takes its launch plus its busiest SM, or the DRAM bandwidth
// bound of its DRAM sectors if that is slower (then the bound says so).
void FinishKernelCycles(BatchCost& cost, std::uint64_t launch_cycles, std::uint64_t busiest_sm_cycles,
                        const GpuParams& gpu);

}  // namespace rc
