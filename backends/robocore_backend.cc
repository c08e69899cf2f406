#include "backends/robocore_backend.h"

#include "backends/modelled_backend.h"

namespace rc {

RoboCoreBackend::RoboCoreBackend(const BackendParameters& params)
    : gpu_(params.gpu), robocore_(params.robocore), energy_(params.energy) {
  specs_ = ModelledBackendSpecs("robocore", "RoboCore units: TTA+ with chained SACT units, CTRL early exit", gpu_);
  specs_.has_rt_unit = true;
  specs_.has_sact_units = true;
  specs_.early_exit = EarlyExitMode::kConditionalReturn;
}

RtUnitPricing RoboCoreBackend::UnitPricing(const KernelRecord& record) const {
  RtUnitPricing pricing;
  pricing.unit = &robocore_.unit;
  pricing.gpu = &gpu_;
  pricing.energy = &energy_;
  pricing.datapath = robocore_.Datapath();
  // Launch: the kernel launch, ConfigRoboCore (the program into every
  // unit's store) and ConfigDecode (one layout per node kind).
  pricing.launch_cycles_besides_program =
      static_cast<std::uint64_t>(robocore_.decode_config_cycles_per_layout) * record.regions.size() +
      static_cast<std::uint64_t>(gpu_.kernel_launch_cycles);
  pricing.program_config_cycles_per_micro_op =
      static_cast<std::uint64_t>(robocore_.unit.program_config_cycles_per_micro_op);
  return pricing;
}

}  // namespace rc
