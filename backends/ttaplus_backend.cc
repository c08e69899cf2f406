#include "backends/ttaplus_backend.h"

#include "backends/rt_unit_model.h"

namespace rc {

TtaPlusBackend::TtaPlusBackend(const BackendParameters& params, EarlyExitMode mode)
    : gpu_(params.gpu), ttaplus_(params.ttaplus), energy_(params.energy), mode_(mode) {
  switch (mode) {
    case EarlyExitMode::kNone:
      specs_.name = "ttaplus";
      specs_.description = "TTA+ units, no early exit";
      break;
    case EarlyExitMode::kPredication:
      specs_.name = "ttaplus-p";
      specs_.description = "TTA+ units, early exit by predication";
      break;
    case EarlyExitMode::kConditionalReturn:
      specs_.name = "ttaplus-cr";
      specs_.description = "TTA+ units, early exit by conditional return";
      break;
  }
  specs_.has_cost_model = true;
  specs_.has_rt_unit = true;
  specs_.early_exit = mode;
  specs_.step_programs = {StepProgramKind::kGridMarch, StepProgramKind::kDdaStep,
                          StepProgramKind::kRmStep, StepProgramKind::kSactTest,
                          StepProgramKind::kBallQueryPRay, StepProgramKind::kBallQueryPSphere};
  specs_.clock_hz = gpu_.core_clock_hz;
  specs_.sms = gpu_.sms;
}

BatchCost TtaPlusBackend::DoPrice(const KernelRecord& record, PricingContext& context) const {
  RtUnitPricing pricing;
  pricing.unit = &ttaplus_.unit;
  pricing.gpu = &gpu_;
  pricing.energy = &energy_;
  pricing.datapath = ttaplus_.Datapath(mode_);
  pricing.launch_cycles =
      static_cast<std::uint64_t>(gpu_.kernel_launch_cycles) +
      ProgramStoreMicroOps(record, pricing.datapath) *
          static_cast<std::uint64_t>(ttaplus_.unit.program_config_cycles_per_micro_op);
  return PriceOnRtUnit(record, context, pricing, specs_.name);
}

}  // namespace rc
