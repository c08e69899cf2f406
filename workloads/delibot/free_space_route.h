#pragma once
// Collision-free routes for a disc robot through any occupancy grid, for the
// trace simulator (and anything else that needs to drive a robot around a
// map it did not make).
//
// Method: the blocking cells (occupied, unknown, and the outside of the map)
// are inflated by the robot radius with the exact distance field
// (DistanceTarget::kBlocking). A cell is "safe" when every point of it is at
// least the radius away from every blocking cell; the reachable space is the
// largest 4-connected component of safe cells. Waypoints are seeded random
// reachable cell centres; consecutive ones are joined by 8-connected grid A*
// without corner cutting, and each leg is string-pulled with a conservative
// line-of-sight test, so the robot drives straight segments and turns in
// place between them (a disc's footprint does not change when it turns).
//
// Why the route is safe at every point, not only at cell centres: a safe
// cell's centre is at least radius + sqrt(2) * resolution from every blocking
// cell centre, and any point of the cell is then at least `radius` from every
// point of every blocking cell (two half-diagonals of slack). A segment is
// accepted only if every cell it touches (both side cells at an exact corner
// crossing) is safe.
//
// Memory: a byte per cell for the reachable mask plus a 4-byte index per
// reachable cell; A* allocates 13 bytes per cell per leg. Precomputation: one
// distance transform (linear in the cell count) and one flood fill.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "maps/occupancy_grid.h"

namespace rc {

// A point in the map frame (m).
struct RoutePoint {
  double x_m = 0.0;
  double y_m = 0.0;
};

class RandomStream;

// The map leaves a disc robot nowhere to drive: no free cell, or no free
// cell wide enough for it. The map's fault, not a bug, so a caller that knows
// the map's file reports it as bad input.
class NoRoomToDrive : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// The free space a disc robot of a given radius can reach.
class ReachableFreeSpace {
 public:
  // Throws std::invalid_argument when the radius is not positive and finite;
  // NoRoomToDrive when the grid has no free cell or none wide enough for
  // the robot (the message gives the widest clearance the map offers).
  ReachableFreeSpace(const OccupancyGrid& grid, double robot_radius_m);

  double robot_radius_m() const { return robot_radius_m_; }
  double resolution_m() const { return resolution_m_; }
  int size_x() const { return size_x_; }
  int size_y() const { return size_y_; }
  // Cells of the largest component, in storage order (ix * size_y + iy).
  const std::vector<std::uint32_t>& reachable_cells() const { return reachable_cells_; }

  bool IsReachableCell(int ix, int iy) const;
  bool IsReachablePoint(const RoutePoint& p) const;
  // True if every point of the segment lies in a reachable cell (so the disc
  // robot can drive it). Conservative at exact cell-corner crossings.
  bool SegmentIsReachable(const RoutePoint& a, const RoutePoint& b) const;

  // The centre of a uniformly drawn reachable cell.
  RoutePoint DrawCellCentre(RandomStream& stream) const;
  // A uniformly drawn point of a uniformly drawn reachable cell.
  RoutePoint DrawPoint(RandomStream& stream) const;

  // A smoothed collision-free polyline from a to b: the first vertex is a,
  // the last is b, consecutive vertices differ (a single vertex if a == b).
  // Throws std::invalid_argument if a or b is not reachable.
  std::vector<RoutePoint> PlanPath(const RoutePoint& a, const RoutePoint& b) const;

 private:
  std::vector<std::uint32_t> GridAStar(std::uint32_t start, std::uint32_t goal) const;
  RoutePoint CellCentre(std::uint32_t index) const;

  double robot_radius_m_ = 0.0;
  double resolution_m_ = 0.0;
  int size_x_ = 0;
  int size_y_ = 0;
  std::vector<std::uint8_t> reachable_;  // 1 = in the largest component
  std::vector<std::uint32_t> reachable_cells_;
};

struct FreeSpaceRouteOptions {
  double robot_radius_m = 0.2;  // disc robot radius (m), (0, 10]
  int waypoint_count = 8;       // K random waypoints, [2, 10^6]
  std::uint64_t seed = 1;       // waypoint draws

  bool IsValid(std::string* error) const;
};

struct FreeSpaceRoute {
  // The drawn waypoints (reachable cell centres, map frame) with consecutive
  // repeats removed; the route visits them in order.
  std::vector<RoutePoint> waypoints;
  // The smoothed route from waypoints.front() to waypoints.back(); it passes
  // exactly through every waypoint. Consecutive vertices differ.
  std::vector<RoutePoint> polyline;
};

// Waypoint `index` of the seeded waypoint sequence: a reachable cell centre
// from RandomStream(seed, kSimulation, index, 0). Callers that extend a route
// beyond its K waypoints continue the same sequence with index >= K.
RoutePoint DrawRouteWaypoint(const ReachableFreeSpace& space, std::uint64_t seed, std::uint64_t index);

// Draws options.waypoint_count waypoints and connects them. Throws
// std::invalid_argument for invalid options, for the grid errors of
// ReachableFreeSpace, and when fewer than 2 distinct waypoints remain (the
// reachable space is a single cell, or every draw hit the same cell).
FreeSpaceRoute PlanFreeSpaceRoute(const OccupancyGrid& grid, const FreeSpaceRouteOptions& options);
// The same on a reachable space built already (for callers that keep it to
// plan further legs with PlanPath).
FreeSpaceRoute PlanFreeSpaceRoute(const ReachableFreeSpace& space, int waypoint_count, std::uint64_t seed);

}  // namespace rc
