#include "backends/calibration/sact_kernel_record.h"

#include <stdexcept>
#include <vector>

#include "robocore/shipped_programs.h"

namespace rc {

KernelRecord SactKernelRecord(const CollisionBatch& batch) {
  if (batch.sphere_pretests)
    throw std::invalid_argument("SactKernelRecord: the shipped SACT program has no sphere pre-test section");
  MemoryRegion region;
  region.name = "box tree nodes";
  // robocore has no tree-node fetch kind; the cost models use only the
  // region's bytes and addresses.
  region.kind = FetchKind::kGridCell;
  region.base = batch.base_address;
  region.element_bytes = batch.node_bytes;
  region.elements = batch.node_count;
  KernelRecordBuilder builder(ShippedStepProgram(StepProgramKind::kSactTest), StepProgramKind::kSactTest, region);
  std::vector<std::uint64_t> addresses;
  std::vector<std::uint8_t> exits;
  for (std::size_t q = 0; q < batch.query_count(); ++q) {
    addresses.clear();
    exits.clear();
    for (std::uint64_t k = batch.visit_offsets[q]; k < batch.visit_offsets[q + 1]; ++k) {
      const NodeVisit& v = batch.visits[k];
      addresses.push_back(batch.Address(v));
      exits.push_back(v.exit >= 0 ? static_cast<std::uint8_t>(v.exit) : kNoExit);
    }
    builder.AddQuery(addresses, exits);
  }
  return builder.Build();
}

}  // namespace rc
