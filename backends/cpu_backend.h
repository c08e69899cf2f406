#pragma once
// The CPU reference: runs the kernels on the host (OpenMP) and reports the
// host wall time. It has no cost model: Price says so (modelled = false) and
// returns the batch's size only.
#include "backends/backend.h"

namespace rc {

class CpuBackend final : public Backend {
 public:
  CpuBackend();
  const BackendSpecs& specs() const override { return specs_; }
  BatchCost Run(const RayCastScene& scene, const RayBatch& batch, std::vector<RayHit>& hits) const override;

 protected:
  BatchCost DoPrice(const KernelRecord& record, PricingContext& context) const override;

 private:
  BackendSpecs specs_;
};

}  // namespace rc
