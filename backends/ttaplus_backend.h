#pragma once
// TTA+: a programmable tree-traversal accelerator, one unit per SM, running
// each step program as micro-ops through its OP units (paper's latencies),
// paying an interconnect hop whenever consecutive micro-ops of a thread run
// on different units. It has no SACT units: SACT micro-ops run as their
// TTA+ expansion (robocore/micro_op.h). Three early-exit modes, from the
// backend name:
//   ttaplus     no early exit: RETURN_IF markers are dropped and every
//               micro-op of every pass runs. Unlike the artifact, a RETURN
//               does not predicate later micro-ops off in this mode (the
//               artifact bug of REFERENCE.md section 2, which made its plain
//               TTA+ optimistic); a test guards this.
//   ttaplus-p   predication: after a fired RETURN_IF the remaining micro-ops
//               still travel and take one slot each.
//   ttaplus-cr  conditional return: a fired RETURN_IF ends the pass.
// Launch: the kernel launch plus writing the (lowered) program into every
// unit's program store. The unit model is rt_unit_model.h.
#include "backends/rt_unit_model.h"

namespace rc {

class TtaPlusBackend final : public RtUnitBackend {
 public:
  TtaPlusBackend(const BackendParameters& params, EarlyExitMode mode);
  const BackendSpecs& specs() const override { return specs_; }

 private:
  RtUnitPricing UnitPricing(const KernelRecord& record) const override;

  GpuParams gpu_;
  TtaPlusParams ttaplus_;
  EnergyParams energy_;
  EarlyExitMode mode_;
  BackendSpecs specs_;
};

}  // namespace rc
