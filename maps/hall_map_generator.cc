#include "maps/hall_map_generator.h"

#include <cmath>
#include <vector>

#include "common/input_error.h"
#include "common/random_stream.h"
#include "maps/metric_rect.h"

namespace rc {
namespace {

constexpr double kMinResolutionM = 0.05;
constexpr double kMaxResolutionM = 0.2;
constexpr double kWallM = 0.3;
constexpr double kOpenHallStartM = 20.0;
constexpr double kPalletClearanceM = 1.5;  // keeps every pallet off every other obstacle
constexpr int kPalletCount = 12;
constexpr int kPlacementTries = 50;

}  // namespace

bool HallMapOptions::IsValid(std::string* error) const {
  if (!(resolution_m >= kMinResolutionM && resolution_m <= kMaxResolutionM)) {
    *error = "hall map resolution must be in [" + std::to_string(kMinResolutionM) + ", " +
             std::to_string(kMaxResolutionM) + "] m per cell, got " + std::to_string(resolution_m);
    return false;
  }
  return true;
}

OccupancyGrid GenerateHallMap(const HallMapOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw UsageError(error);
  const int size_x = static_cast<int>(std::lround(kHallWidthM / options.resolution_m));
  const int size_y = static_cast<int>(std::lround(kHallHeightM / options.resolution_m));
  OccupancyGrid grid(size_x, size_y, options.resolution_m, CellState::kFree);

  std::vector<MetricRect> obstacles = {
      {0.0, 0.0, kHallWidthM, kWallM},                          // south wall
      {0.0, kHallHeightM - kWallM, kHallWidthM, kHallHeightM},  // north wall
      {0.0, 0.0, kWallM, kHallHeightM},                         // west wall
      {kHallWidthM - kWallM, 0.0, kHallWidthM, kHallHeightM},   // east wall
  };
  for (int row = 0; row < 4; ++row) {  // racks: y = 6, 14, 22, 30 m
    const double y0 = 6.0 + 8.0 * row;
    obstacles.push_back({2.0, y0, 18.0, y0 + 1.0});
  }
  for (int col = 0; col < 4; ++col) {  // pillars: x = 25..55 m; odd columns shifted 5 m north
    for (double y = (col % 2 ? 10.0 : 5.0); y < kHallHeightM - 2.0; y += 10.0) {
      const double x = 25.0 + 10.0 * col;
      obstacles.push_back({x - 0.3, y - 0.3, x + 0.3, y + 0.3});
    }
  }
  for (const MetricRect& r : obstacles) FillRect(r, CellState::kOccupied, &grid);
  CloseBorder(&grid);

  RandomStream rng(options.seed, StreamPurpose::kMapGeneration, 1, 0);
  for (int placed = 0, tries = 0; placed < kPalletCount && tries < kPalletCount * kPlacementTries; ++tries) {
    const bool turned = rng.Uniform() < 0.5;
    const double w = turned ? 1.0 : 1.2, h = turned ? 1.2 : 1.0;
    const double x0 = rng.Uniform(kOpenHallStartM + kPalletClearanceM, kHallWidthM - kWallM - kPalletClearanceM - w);
    const double y0 = rng.Uniform(kWallM + kPalletClearanceM, kHallHeightM - kWallM - kPalletClearanceM - h);
    const MetricRect pallet{x0, y0, x0 + w, y0 + h};
    bool clear = true;
    for (const MetricRect& o : obstacles)
      clear = clear && !Overlaps(Inflate(pallet, kPalletClearanceM, kPalletClearanceM), o);
    if (!clear) continue;
    FillRect(pallet, CellState::kOccupied, &grid);
    obstacles.push_back(pallet);
    ++placed;
  }
  return grid;
}

}  // namespace rc
