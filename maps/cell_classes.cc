#include "maps/cell_classes.h"

#include <fmt/format.h>

namespace rc {
namespace {

std::string Grouped(std::size_t n) {
  std::string digits = std::to_string(n), out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

std::string Percent(std::size_t part, std::size_t whole) {
  return fmt::format("{:.1f}%", whole ? 100.0 * static_cast<double>(part) / static_cast<double>(whole) : 0.0);
}

}  // namespace

std::string CellClassCounts::Describe() const {
  const std::size_t total = Total();
  const std::size_t observed = total - Of(CellClass::kUnobserved);
  auto part = [&](const char* name, CellClass c) {
    return std::string(name) + " " + Grouped(Of(c)) + " (" + Percent(Of(c), total) + ")";
  };
  std::string text = part("free", CellClass::kFree) + ", " + part("occupied", CellClass::kOccupied) +
                     ", unknown: " + "between thresholds " + Grouped(Of(CellClass::kBetweenThresholds)) + " (" +
                     Percent(Of(CellClass::kBetweenThresholds), total) + " of all, " +
                     Percent(Of(CellClass::kBetweenThresholds), observed) + " of observed)";
  return text + ", " + part("never observed", CellClass::kUnobserved);
}

CellClassCounts CountStates(const OccupancyGrid& grid) {
  CellClassCounts counts;
  for (CellState s : grid.cells())
    counts.Add(s == CellState::kFree       ? CellClass::kFree
               : s == CellState::kOccupied ? CellClass::kOccupied
                                           : CellClass::kUnobserved);
  return counts;
}

}  // namespace rc
