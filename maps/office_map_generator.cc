#include "maps/office_map_generator.h"

#include <algorithm>
#include <cmath>

#include "common/input_error.h"
#include "common/random_stream.h"
#include "maps/grid_connectivity.h"

namespace rc {
namespace {

constexpr double kMinResolutionM = 0.02;
constexpr double kMaxResolutionM = 0.1;
// Passage kept between furniture and anything else unless it is flush with a
// wall: wide enough for a small robot.
constexpr double kFurnitureClearanceM = 0.7;
// Furniture stays this far from a doorway, on both sides of the wall.
constexpr double kDoorKeepOutDepthM = 1.2;
constexpr double kDoorKeepOutSideM = 0.3;
constexpr int kPlacementTries = 30;

// clang-format off
// Walls (0.2 m thick). The interior walls stop at the outer walls' inner
// faces, so no gap can open where they meet.
const MetricRect kWalls[] = {
    {0.0, 0.0, 20.0, 0.2},     {0.0, 14.8, 20.0, 15.0},    // south, north outer
    {0.0, 0.0, 0.2, 15.0},     {19.8, 0.0, 20.0, 15.0},    // west, east outer
    {0.2, 6.0, 15.2, 6.2},     {0.2, 8.2, 15.2, 8.4},      // corridor south, north
    {15.0, 0.2, 15.2, 6.2},    {15.0, 8.2, 15.2, 14.8},    // lobby partition
    {5.0, 0.2, 5.2, 6.0},      {9.5, 0.2, 9.7, 6.0},       // south rooms
    {7.5, 8.4, 7.7, 14.8},                                  // north rooms
    {11.8, 11.6, 15.0, 11.8},  {11.8, 11.8, 12.0, 14.8},   // storage room
};

const std::vector<MetricRect> kDoors = {
    {3.4, 6.0, 4.5, 6.2},     // room S1 (west) to corridor
    {5.8, 6.0, 6.9, 6.2},     // room S2
    {12.6, 6.0, 13.8, 6.2},   // room S3
    {15.0, 1.0, 15.2, 2.1},   // room S3 to lobby
    {1.2, 8.2, 2.5, 8.4},     // conference room N1
    {9.0, 8.2, 10.1, 8.4},    // north office N2, west door
    {13.3, 8.2, 14.4, 8.4},   // north office N2, east door
    {11.8, 12.6, 12.0, 13.7}, // storage room from N2
    {15.0, 6.2, 15.2, 8.2},   // corridor mouth into the lobby
};

// Fixed obstacles: lobby pillars, reception counter, conference table and a
// pillar in the north office.
const MetricRect kFixedObstacles[] = {
    {16.4, 3.0, 16.8, 3.4},  {18.2, 10.6, 18.6, 11.0}, {16.6, 12.7, 17.0, 13.1},
    {17.9, 5.0, 18.7, 7.6},  {2.6, 10.6, 5.4, 12.2},   {10.2, 10.8, 10.6, 11.2},
};

// Rooms that receive random furniture (interiors; the storage walls inside
// N2 are avoided by the free-cell check).
const MetricRect kRooms[] = {
    {0.2, 0.2, 5.0, 6.0},   {5.2, 0.2, 9.5, 6.0},   {9.7, 0.2, 15.0, 6.0},  // S1 S2 S3
    {0.2, 8.4, 7.5, 14.8},  {7.7, 8.4, 15.0, 14.8}, {12.0, 11.8, 15.0, 14.8},  // N1 N2 N3
    {15.2, 0.2, 19.8, 14.8},                                                   // lobby
};

// Desk, cabinet, table, shelf (width x depth, m).
const double kFurnitureSizes[][2] = {{1.4, 0.7}, {1.0, 0.45}, {0.9, 0.9}, {1.8, 0.4}};
// clang-format on

MetricRect DoorKeepOut(const MetricRect& door) {
  const bool in_horizontal_wall = (door.x1_m - door.x0_m) > (door.y1_m - door.y0_m);
  return in_horizontal_wall ? Inflate(door, kDoorKeepOutSideM, kDoorKeepOutDepthM)
                            : Inflate(door, kDoorKeepOutDepthM, kDoorKeepOutSideM);
}

// Moves a piece flush against any room wall it is closer to than the
// clearance, so it never leaves a sliver of free space behind it.
MetricRect SnapToWalls(MetricRect f, const MetricRect& room) {
  const double w = f.x1_m - f.x0_m, h = f.y1_m - f.y0_m;
  if (f.x0_m - room.x0_m < kFurnitureClearanceM) f.x0_m = room.x0_m, f.x1_m = room.x0_m + w;
  if (room.x1_m - f.x1_m < kFurnitureClearanceM) f.x1_m = room.x1_m, f.x0_m = room.x1_m - w;
  if (f.y0_m - room.y0_m < kFurnitureClearanceM) f.y0_m = room.y0_m, f.y1_m = room.y0_m + h;
  if (room.y1_m - f.y1_m < kFurnitureClearanceM) f.y1_m = room.y1_m, f.y0_m = room.y1_m - h;
  return f;
}

// Tries to place one random piece in room; returns whether it stayed.
bool PlaceFurniture(const MetricRect& room, RandomStream& rng, std::vector<MetricRect>* avoid, OccupancyGrid* grid) {
  const auto& size = kFurnitureSizes[rng.Below(std::size(kFurnitureSizes))];
  const bool rotated = rng.Uniform() < 0.5;
  const double w = rotated ? size[1] : size[0];
  const double h = rotated ? size[0] : size[1];
  for (int attempt = 0; attempt < kPlacementTries; ++attempt) {
    const double x0 = rng.Uniform(room.x0_m, room.x1_m - w);
    const double y0 = rng.Uniform(room.y0_m, room.y1_m - h);
    const MetricRect piece = SnapToWalls({x0, y0, x0 + w, y0 + h}, room);
    const MetricRect halo = Inflate(piece, kFurnitureClearanceM, kFurnitureClearanceM);
    if (std::any_of(avoid->begin(), avoid->end(), [&](const MetricRect& a) { return Overlaps(halo, a); })) continue;
    if (!AllFree(piece, *grid)) continue;  // walls (e.g. the storage room's) or pillars
    FillRect(piece, CellState::kOccupied, grid);
    if (CountFreeComponents(*grid) != 1) {
      FillRect(piece, CellState::kFree, grid);  // every cell under it was free
      continue;
    }
    avoid->push_back(piece);
    return true;
  }
  return false;
}

}  // namespace

bool OfficeMapOptions::IsValid(std::string* error) const {
  if (!(resolution_m >= kMinResolutionM && resolution_m <= kMaxResolutionM)) {
    *error = "office map resolution must be in [" + std::to_string(kMinResolutionM) + ", " +
             std::to_string(kMaxResolutionM) + "] m per cell, got " + std::to_string(resolution_m);
    return false;
  }
  return true;
}

const std::vector<MetricRect>& OfficeDoorOpenings() { return kDoors; }

OccupancyGrid GenerateOfficeMap(const OfficeMapOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw UsageError(error);
  const int size_x = static_cast<int>(std::lround(kOfficeWidthM / options.resolution_m));
  const int size_y = static_cast<int>(std::lround(kOfficeHeightM / options.resolution_m));
  OccupancyGrid grid(size_x, size_y, options.resolution_m, CellState::kFree);

  for (const auto& wall : kWalls) FillRect(wall, CellState::kOccupied, &grid);
  CloseBorder(&grid);
  for (const auto& door : kDoors) FillRect(door, CellState::kFree, &grid);

  std::vector<MetricRect> avoid;
  for (const auto& door : kDoors) avoid.push_back(DoorKeepOut(door));
  for (const auto& obstacle : kFixedObstacles) {
    FillRect(obstacle, CellState::kOccupied, &grid);
    avoid.push_back(obstacle);
  }
  // One stream per room keeps a room's furniture independent of the others'.
  for (std::size_t room = 0; room < std::size(kRooms); ++room) {
    RandomStream rng(options.seed, StreamPurpose::kMapGeneration, 0, room);
    const int pieces = 2 + static_cast<int>(rng.Below(3));
    for (int i = 0; i < pieces; ++i) PlaceFurniture(kRooms[room], rng, &avoid, &grid);
  }
  return grid;
}

}  // namespace rc
