#pragma once
// Dynamic energy from event counts and the Horowitz 45 nm figures
// (gpu_params.h, EnergyParams). Leakage is not modelled.
#include "backends/gpu_params.h"
#include "backends/memory_replay.h"
#include "robocore/micro_op.h"

namespace rc {

// Arithmetic of micro-ops or instructions: FP32 adds and multiplies,
// reciprocals, integer/logic operations.
double ArithmeticEnergyJoules(const ArithmeticContent& work, const EnergyParams& e);

// Every sector request reads the L1, every L1 miss the L2, every L2 miss
// DRAM; each moves one sector (sector_bytes / 8 64-bit accesses).
double MemoryEnergyJoules(const MemoryCounters& memory, const GpuParams& gpu, const EnergyParams& e);

// Accesses of the 8 KB / 32 KB SRAM figures, in joules.
inline double Sram8kbJoules(double accesses, const EnergyParams& e) { return accesses * e.sram_8kb_pj * 1e-12; }
inline double Sram32kbJoules(double accesses, const EnergyParams& e) { return accesses * e.sram_32kb_pj * 1e-12; }

}  // namespace rc
