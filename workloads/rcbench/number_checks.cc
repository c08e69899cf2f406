#include "workloads/rcbench/number_checks.h"

#include <cmath>
#include <string>

namespace rc {
namespace {

// Reads `text` as CLI11 would and returns "" when `accept` holds, else why not.
template <class Accept>
std::string Check(const std::string& text, const char* wanted, Accept accept) {
  double value = 0.0;
  if (!CLI::detail::lexical_cast(text, value)) return "'" + text + "' is not a number";
  if (!accept(value)) return "'" + text + "' is not " + wanted;
  return "";
}

}  // namespace

const CLI::Validator& FinitePositive() {
  static const CLI::Validator check(
      [](std::string& text) {
        return Check(text, "a finite number > 0", [](double v) { return std::isfinite(v) && v > 0.0; });
      },
      "FINITE > 0", "FinitePositive");
  return check;
}

const CLI::Validator& Finite() {
  static const CLI::Validator check(
      [](std::string& text) { return Check(text, "a finite number", [](double v) { return std::isfinite(v); }); },
      "FINITE", "Finite");
  return check;
}

}  // namespace rc
