#include "backends/ttaplus_backend.h"

#include "backends/modelled_backend.h"

namespace rc {

TtaPlusBackend::TtaPlusBackend(const BackendParameters& params, EarlyExitMode mode)
    : gpu_(params.gpu), ttaplus_(params.ttaplus), energy_(params.energy), mode_(mode) {
  switch (mode) {
    case EarlyExitMode::kNone: specs_ = ModelledBackendSpecs("ttaplus", "TTA+ units, no early exit", gpu_); break;
    case EarlyExitMode::kPredication:
      specs_ = ModelledBackendSpecs("ttaplus-p", "TTA+ units, early exit by predication", gpu_);
      break;
    case EarlyExitMode::kConditionalReturn:
      specs_ = ModelledBackendSpecs("ttaplus-cr", "TTA+ units, early exit by conditional return", gpu_);
      break;
  }
  specs_.has_rt_unit = true;
  specs_.early_exit = mode;
}

RtUnitPricing TtaPlusBackend::UnitPricing(const KernelRecord& /*record*/) const {
  RtUnitPricing pricing;
  pricing.unit = &ttaplus_.unit;
  pricing.gpu = &gpu_;
  pricing.energy = &energy_;
  pricing.datapath = ttaplus_.Datapath(mode_);
  pricing.launch_cycles_besides_program = static_cast<std::uint64_t>(gpu_.kernel_launch_cycles);
  pricing.program_config_cycles_per_micro_op =
      static_cast<std::uint64_t>(ttaplus_.unit.program_config_cycles_per_micro_op);
  return pricing;
}

}  // namespace rc
