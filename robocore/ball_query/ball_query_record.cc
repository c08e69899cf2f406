#include "robocore/ball_query/ball_query_record.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "robocore/shipped_programs.h"

namespace rc {

StepProgramKind BallQueryProgramKind(BallQueryFormulation formulation) {
  return formulation == BallQueryFormulation::kPRay ? StepProgramKind::kBallQueryPRay
                                                    : StepProgramKind::kBallQueryPSphere;
}

BallQueryRecorder::BallQueryRecorder(BallQueryFormulation formulation, std::size_t dimension,
                                     std::uint64_t base_address)
    : formulation_(formulation), node_bytes_(BallQueryTree::NodeBytes(dimension)), base_(base_address) {
  if (dimension > kMaxRecordedDimension)
    throw std::invalid_argument("ball query: dimension " + std::to_string(dimension) +
                                " cannot be recorded; the shipped programs describe at most " +
                                std::to_string(kMaxRecordedDimension) +
                                " coordinates (set BallQueryConfig::record = false)");
  Reset();
}

void BallQueryRecorder::Reset() {
  record_ = KernelRecord{};
  record_.step_kind = BallQueryProgramKind(formulation_);
  record_.program = ShippedStepProgram(record_.step_kind);
  record_.node_bytes = node_bytes_;
  slots_ = 0;
}

void BallQueryRecorder::AddQuery(const BallQueryVisits& visits, std::size_t node_slots) {
  slots_ = std::max<std::uint64_t>(slots_, node_slots);
  for (std::uint32_t node : visits.nodes) record_.fetch_addresses.push_back(base_ + std::uint64_t{node} * node_bytes_);
  record_.node_exits.insert(record_.node_exits.end(), visits.exits.begin(), visits.exits.end());
  record_.fetch_offsets.push_back(record_.fetch_addresses.size());
}

KernelRecord BallQueryRecorder::Take() {
  if (record_.query_count() > 0) {
    MemoryRegion region;
    region.name = "ball-query BVH nodes";
    region.kind = FetchKind::kGridCell;  // robocore has no tree-node kind; costs use bytes and addresses only
    region.base = base_;
    region.element_bytes = node_bytes_;
    region.elements = std::max<std::uint64_t>(slots_, 1);
    record_.regions.push_back(region);
    record_.Validate();
  }
  KernelRecord out = std::move(record_);
  Reset();
  return out;
}

}  // namespace rc
