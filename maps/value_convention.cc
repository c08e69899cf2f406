#include "maps/value_convention.h"

#include <stdexcept>

namespace rc {

ValueConvention ParseValueConvention(const std::string& name) {
  if (name == "free" || name == "p-free") return ValueConvention::kProbabilityFree;
  if (name == "occupied" || name == "p-occupied") return ValueConvention::kProbabilityOccupied;
  throw std::invalid_argument("unknown value convention '" + name +
                              "' (expected 'free' or 'occupied')");
}

std::string ToString(ValueConvention c) {
  return c == ValueConvention::kProbabilityFree ? "free" : "occupied";
}

}  // namespace rc
