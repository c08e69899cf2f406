#include "backends/energy_model.h"

namespace rc {

double ArithmeticEnergyJoules(const ArithmeticContent& w, const EnergyParams& e) {
  const double pj = w.fp_adds * e.fp32_add_pj + w.fp_muls * e.fp32_mul_pj + w.reciprocals * e.fp32_reciprocal_pj +
                    w.int_ops * e.int32_add_pj;
  return pj * 1e-12;
}

double MemoryEnergyJoules(const MemoryCounters& m, const GpuParams& gpu, const EnergyParams& e) {
  const double words = gpu.sector_bytes / 8.0;  // 64-bit accesses per sector
  const double pj =
      words * (static_cast<double>(m.sector_requests) * e.sram_32kb_pj +
               static_cast<double>(m.l2_accesses) * e.sram_1mb_pj + static_cast<double>(m.dram_accesses) * e.dram_pj);
  return pj * 1e-12;
}

}  // namespace rc
