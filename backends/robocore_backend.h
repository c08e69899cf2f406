#pragma once
// RoboCore: TTA+ plus three chained SACT units (Pre-Process 14, Box-Normal
// 12, Edge x Edge 12 cycles; four-stage pipelines). A CTRL block between
// them counts each query's axes and ends the program at a separating axis;
// chained SACT packets skip the interconnect and win the units' input
// arbiter. RETURN ends a program (conditional return), and PUSH counts the
// nodes a query visits (for the adaptive scheduler).
//
// In the batch model, the SACT units show up in the section timing
// (robocore/section_timing.h): native PRE/BOX/EDGE latencies, no hops along
// the chain, CTRL-folded returns, and SACT initiation intervals of
// ceil(latency / stages). The arbiter matters under contention and is
// modelled in robocore/function_unit_simulator.h. The ray-cast step programs
// use no SACT micro-ops, so on them RoboCore times like TTA+-cr; it differs
// in its launch (program plus decode configuration).
#include "backends/rt_unit_model.h"

namespace rc {

class RoboCoreBackend final : public RtUnitBackend {
 public:
  explicit RoboCoreBackend(const BackendParameters& params);
  const BackendSpecs& specs() const override { return specs_; }

 private:
  RtUnitPricing UnitPricing(const KernelRecord& record) const override;

  GpuParams gpu_;
  RoboCoreParams robocore_;
  EnergyParams energy_;
  BackendSpecs specs_;
};

}  // namespace rc
