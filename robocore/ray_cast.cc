#include "robocore/ray_cast.h"

#include <chrono>
#include <stdexcept>

namespace rc {

RayCastMethod ParseRayCastMethod(const std::string& name) {
  if (name == "march") return RayCastMethod::kMarch;
  if (name == "dda") return RayCastMethod::kDda;
  if (name == "rm") return RayCastMethod::kRayMarching;
  throw std::invalid_argument("unknown ray caster '" + name + "' (expected march, dda or rm)");
}

std::string ToString(RayCastMethod m) {
  switch (m) {
    case RayCastMethod::kMarch: return "march";
    case RayCastMethod::kDda: return "dda";
    case RayCastMethod::kRayMarching: return "rm";
  }
  return "?";
}

RayCastScene::RayCastScene(const OccupancyGrid& grid, RayCastMethod method) : grid_(&grid), method_(method) {
  if (method == RayCastMethod::kRayMarching) {
    const auto start = std::chrono::steady_clock::now();
    distance_field_ = std::make_shared<const DistanceField>(DistanceField::Build(grid, DistanceTarget::kBlocking));
    build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  if (method != RayCastMethod::kRayMarching) {
    gather_cells_ = grid.cells();
    gather_cells_.resize(grid.cell_count() + kGatherPadding, CellState::kFree);
  }
}

std::size_t RayCastScene::precomputed_bytes() const { return distance_field_ ? distance_field_->memory_bytes() : 0; }

}  // namespace rc
