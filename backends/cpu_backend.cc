#include "backends/cpu_backend.h"

#include <chrono>

namespace rc {

CpuBackend::CpuBackend() {
  specs_.name = "cpu";
  specs_.description = "host reference (OpenMP); no cost model, host wall time only";
  specs_.has_cost_model = false;
  specs_.step_programs = {StepProgramKind::kGridMarch, StepProgramKind::kDdaStep, StepProgramKind::kRmStep};
}

BatchCost CpuBackend::DoPrice(const KernelRecord& record, PricingContext&) const {
  BatchCost cost;
  cost.backend = specs_.name;
  cost.modelled = false;
  cost.queries = record.query_count();
  cost.nodes = record.total_nodes();
  return cost;
}

BatchCost CpuBackend::Run(const RayCastScene& scene, const RayBatch& batch, std::vector<RayHit>& hits) const {
  const auto start = std::chrono::steady_clock::now();
  CastRayBatch(scene, batch, hits);
  BatchCost cost;
  cost.backend = specs_.name;
  cost.host_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  cost.queries = batch.queries.size();
  cost.nodes = TotalNodes(hits);
  return cost;
}

}  // namespace rc
