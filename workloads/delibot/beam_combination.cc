#include "workloads/delibot/beam_combination.h"

#include <stdexcept>

namespace rc {

const char* ToString(BeamCombination combination) {
  return combination == BeamCombination::kAmclCubeSum ? "amcl-cube" : "product";
}

BeamCombination ParseBeamCombination(const std::string& name) {
  if (name == "product") return BeamCombination::kProduct;
  if (name == "amcl-cube") return BeamCombination::kAmclCubeSum;
  throw std::invalid_argument("unknown beam combination '" + name + "' (product | amcl-cube)");
}

}  // namespace rc
