#include "maps/value_convention.h"

#include <cmath>
#include <sstream>

#include "common/input_error.h"

namespace rc {

ValueConvention ParseValueConvention(const std::string& name) {
  if (name == "free" || name == "p-free") return ValueConvention::kProbabilityFree;
  if (name == "occupied" || name == "p-occupied") return ValueConvention::kProbabilityOccupied;
  throw UsageError("unknown value convention '" + name + "' (expected 'free' or 'occupied')");
}

std::string ToString(ValueConvention c) { return c == ValueConvention::kProbabilityFree ? "free" : "occupied"; }

void CheckProbabilityThresholds(const ProbabilityThresholds& t) {
  auto text = [](double v) {
    std::ostringstream out;
    out << v;
    return out.str();
  };
  if (!std::isfinite(t.occupied_thresh) || t.occupied_thresh < 0.0 || t.occupied_thresh > 1.0)
    throw UsageError("--occupied-thresh must be a probability in [0, 1], got " + text(t.occupied_thresh));
  if (!std::isfinite(t.free_thresh) || t.free_thresh < 0.0 || t.free_thresh > 1.0)
    throw UsageError("--free-thresh must be a probability in [0, 1], got " + text(t.free_thresh));
  if (!(t.free_thresh < t.occupied_thresh))
    throw UsageError("--free-thresh (" + text(t.free_thresh) + ") must be below --occupied-thresh (" +
                     text(t.occupied_thresh) + ")");
}

}  // namespace rc
