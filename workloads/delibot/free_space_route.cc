#include "workloads/delibot/free_space_route.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <queue>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

#include "common/random_stream.h"
#include "maps/distance_field.h"

namespace rc {
namespace {

constexpr double kSqrt2 = 1.41421356237309504880;
// The distance field is stored as float; this slack (m) keeps a float
// rounded just above the threshold from admitting a cell that is, in exact
// arithmetic, just below it.
constexpr double kClearanceSlackM = 1e-6;
// Boundary-crossing times (segment fraction) closer than this count as an
// exact corner crossing, where both side cells are checked.
constexpr double kCornerTieFraction = 1e-9;

bool SamePoint(const RoutePoint& a, const RoutePoint& b) { return a.x_m == b.x_m && a.y_m == b.y_m; }

std::string Metres(double v) { return fmt::format("{:.3f} m", v); }

}  // namespace

ReachableFreeSpace::ReachableFreeSpace(const OccupancyGrid& grid, double robot_radius_m)
    : robot_radius_m_(robot_radius_m),
      resolution_m_(grid.resolution_m()),
      size_x_(grid.size_x()),
      size_y_(grid.size_y()) {
  if (!(robot_radius_m > 0.0) || !std::isfinite(robot_radius_m))
    throw std::invalid_argument("robot radius must be a positive number of metres");
  if (grid.CountCells(CellState::kFree) == 0) throw NoRoomToDrive("map has no free cell: there is nowhere to drive");

  const DistanceField field = DistanceField::Build(grid, DistanceTarget::kBlocking);
  const double required_m = robot_radius_m + kSqrt2 * resolution_m_ + kClearanceSlackM;
  std::vector<std::uint8_t> safe(grid.cell_count(), 0);
  double widest_m = 0.0;
  bool any_safe = false;
  for (int ix = 0; ix < size_x_; ++ix) {
    for (int iy = 0; iy < size_y_; ++iy) {
      if (grid.At(ix, iy) != CellState::kFree) continue;
      const double d = field.At(ix, iy);
      widest_m = std::max(widest_m, d);
      if (d >= required_m) {
        safe[grid.Index(ix, iy)] = 1;
        any_safe = true;
      }
    }
  }
  if (!any_safe)
    throw NoRoomToDrive("free space too narrow for a robot of radius " + Metres(robot_radius_m) +
                        ": the widest free cell is " + Metres(widest_m) +
                        " from the nearest blocking cell (centre to centre), the robot needs " + Metres(required_m) +
                        " (radius + sqrt(2) * resolution)");

  // Largest 4-connected component of safe cells. 8-connected moves without
  // corner cutting connect exactly the same cells, so A* stays inside it.
  std::vector<std::int32_t> label(grid.cell_count(), -1);
  std::vector<std::uint32_t> component, best;
  std::int32_t next_label = 0;
  std::deque<std::uint32_t> frontier;
  for (std::uint32_t seed_cell = 0; seed_cell < safe.size(); ++seed_cell) {
    if (!safe[seed_cell] || label[seed_cell] >= 0) continue;
    component.clear();
    label[seed_cell] = next_label;
    frontier.push_back(seed_cell);
    while (!frontier.empty()) {
      const std::uint32_t c = frontier.front();
      frontier.pop_front();
      component.push_back(c);
      const int cx = static_cast<int>(c / size_y_), cy = static_cast<int>(c % size_y_);
      const int nx[4] = {cx + 1, cx - 1, cx, cx};
      const int ny[4] = {cy, cy, cy + 1, cy - 1};
      for (int k = 0; k < 4; ++k) {
        if (!grid.Contains(nx[k], ny[k])) continue;
        const auto n = static_cast<std::uint32_t>(grid.Index(nx[k], ny[k]));
        if (!safe[n] || label[n] >= 0) continue;
        label[n] = next_label;
        frontier.push_back(n);
      }
    }
    ++next_label;
    // Strictly larger: ties go to the component found first in storage
    // order, so the choice is deterministic.
    if (component.size() > best.size()) best.swap(component);
  }
  std::sort(best.begin(), best.end());
  reachable_.assign(grid.cell_count(), 0);
  for (std::uint32_t c : best) reachable_[c] = 1;
  reachable_cells_ = std::move(best);
}

bool ReachableFreeSpace::IsReachableCell(int ix, int iy) const {
  if (ix < 0 || iy < 0 || ix >= size_x_ || iy >= size_y_) return false;
  return reachable_[static_cast<std::size_t>(ix) * size_y_ + iy] != 0;
}

bool ReachableFreeSpace::IsReachablePoint(const RoutePoint& p) const {
  if (!std::isfinite(p.x_m) || !std::isfinite(p.y_m)) return false;
  const double fx = std::floor(p.x_m / resolution_m_), fy = std::floor(p.y_m / resolution_m_);
  if (fx < 0.0 || fy < 0.0 || fx >= size_x_ || fy >= size_y_) return false;
  return IsReachableCell(static_cast<int>(fx), static_cast<int>(fy));
}

bool ReachableFreeSpace::SegmentIsReachable(const RoutePoint& a, const RoutePoint& b) const {
  if (!IsReachablePoint(a) || !IsReachablePoint(b)) return false;
  const double r = resolution_m_;
  int ix = static_cast<int>(std::floor(a.x_m / r)), iy = static_cast<int>(std::floor(a.y_m / r));
  const int ex = static_cast<int>(std::floor(b.x_m / r)), ey = static_cast<int>(std::floor(b.y_m / r));
  const double dx = b.x_m - a.x_m, dy = b.y_m - a.y_m;
  const int sx = ex > ix ? 1 : (ex < ix ? -1 : 0);
  const int sy = ey > iy ? 1 : (ey < iy ? -1 : 0);
  // Time (fraction of the segment) at which the segment leaves the current
  // cell along one axis, from the start point by formula so that no error
  // accumulates over long segments.
  auto exit_time = [&](int cell, int step, double origin, double delta) {
    if (step == 0) return std::numeric_limits<double>::infinity();
    const int boundary = step > 0 ? cell + 1 : cell;
    return (boundary * r - origin) / delta;
  };
  while (ix != ex || iy != ey) {
    const bool x_left = ix != ex, y_left = iy != ey;
    const double tx = x_left ? exit_time(ix, sx, a.x_m, dx) : std::numeric_limits<double>::infinity();
    const double ty = y_left ? exit_time(iy, sy, a.y_m, dy) : std::numeric_limits<double>::infinity();
    if (x_left && y_left && std::abs(tx - ty) <= kCornerTieFraction) {
      // Through (or within rounding of) a cell corner: the segment touches
      // both side cells, so both must be safe.
      if (!IsReachableCell(ix + sx, iy) || !IsReachableCell(ix, iy + sy)) return false;
      ix += sx;
      iy += sy;
    } else if (tx < ty) {
      ix += sx;
    } else {
      iy += sy;
    }
    if (!IsReachableCell(ix, iy)) return false;
  }
  return true;
}

RoutePoint ReachableFreeSpace::CellCentre(std::uint32_t index) const {
  const int ix = static_cast<int>(index / size_y_), iy = static_cast<int>(index % size_y_);
  return {(ix + 0.5) * resolution_m_, (iy + 0.5) * resolution_m_};
}

RoutePoint ReachableFreeSpace::DrawCellCentre(RandomStream& stream) const {
  return CellCentre(reachable_cells_[stream.Below(reachable_cells_.size())]);
}

RoutePoint ReachableFreeSpace::DrawPoint(RandomStream& stream) const {
  const std::uint32_t index = reachable_cells_[stream.Below(reachable_cells_.size())];
  const int ix = static_cast<int>(index / size_y_), iy = static_cast<int>(index % size_y_);
  // 1% of a cell away from its edges, so that rounding of (i + u) * r can
  // never put the point into the neighbouring cell.
  const double ux = stream.Uniform(0.01, 0.99), uy = stream.Uniform(0.01, 0.99);
  return {(ix + ux) * resolution_m_, (iy + uy) * resolution_m_};
}

std::vector<std::uint32_t> ReachableFreeSpace::GridAStar(std::uint32_t start, std::uint32_t goal) const {
  const std::size_t n = reachable_.size();
  std::vector<double> cost(n, std::numeric_limits<double>::infinity());
  std::vector<std::int32_t> parent(n, -1);
  std::vector<std::uint8_t> closed(n, 0);
  const int gx = static_cast<int>(goal / size_y_), gy = static_cast<int>(goal % size_y_);
  // Octile distance in cells: admissible and consistent for these moves.
  auto heuristic = [&](int x, int y) {
    const double ax = std::abs(x - gx), ay = std::abs(y - gy);
    return std::max(ax, ay) + (kSqrt2 - 1.0) * std::min(ax, ay);
  };
  using Entry = std::pair<double, std::uint32_t>;  // (f, cell): ties by index
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> open;
  cost[start] = 0.0;
  open.push({heuristic(static_cast<int>(start / size_y_), static_cast<int>(start % size_y_)), start});
  while (!open.empty()) {
    const std::uint32_t c = open.top().second;
    open.pop();
    if (closed[c]) continue;
    closed[c] = 1;
    if (c == goal) break;
    const int cx = static_cast<int>(c / size_y_), cy = static_cast<int>(c % size_y_);
    for (int mx = -1; mx <= 1; ++mx) {
      for (int my = -1; my <= 1; ++my) {
        if (mx == 0 && my == 0) continue;
        const int nx = cx + mx, ny = cy + my;
        if (!IsReachableCell(nx, ny)) continue;
        // No corner cutting: a diagonal move needs both side cells, so the
        // straight line between the two centres stays in reachable cells.
        if (mx != 0 && my != 0 && (!IsReachableCell(cx + mx, cy) || !IsReachableCell(cx, cy + my))) continue;
        const auto nc = static_cast<std::uint32_t>(static_cast<std::size_t>(nx) * size_y_ + ny);
        const double g = cost[c] + (mx != 0 && my != 0 ? kSqrt2 : 1.0);
        if (g < cost[nc]) {
          cost[nc] = g;
          parent[nc] = static_cast<std::int32_t>(c);
          open.push({g + heuristic(nx, ny), nc});
        }
      }
    }
  }
  if (!closed[goal]) throw std::logic_error("A* found no path between two cells of one connected component");
  std::vector<std::uint32_t> path;
  for (std::int64_t c = goal; c >= 0; c = parent[static_cast<std::size_t>(c)]) {
    path.push_back(static_cast<std::uint32_t>(c));
    if (c == start) break;
  }
  std::reverse(path.begin(), path.end());
  return path;
}

std::vector<RoutePoint> ReachableFreeSpace::PlanPath(const RoutePoint& a, const RoutePoint& b) const {
  if (!IsReachablePoint(a) || !IsReachablePoint(b))
    throw std::invalid_argument("path end point outside the robot's reachable free space");
  if (SamePoint(a, b)) return {a};
  auto cell_of = [&](const RoutePoint& p) {
    const auto ix = static_cast<std::size_t>(std::floor(p.x_m / resolution_m_));
    const auto iy = static_cast<std::size_t>(std::floor(p.y_m / resolution_m_));
    return static_cast<std::uint32_t>(ix * size_y_ + iy);
  };
  const std::vector<std::uint32_t> cells = GridAStar(cell_of(a), cell_of(b));
  // Grid path through the cell centres, with the exact end points. The
  // segment from an end point to the next cell centre is safe by the same
  // argument as a centre-to-centre move: it stays within the 2 x 2 block of
  // cells the move touches.
  std::vector<RoutePoint> grid_path;
  grid_path.push_back(a);
  for (std::size_t i = 1; i + 1 < cells.size(); ++i) grid_path.push_back(CellCentre(cells[i]));
  grid_path.push_back(b);

  // String pulling: from each anchor, go as far along the grid path as the
  // line of sight allows. The fallback (the next grid vertex) is a grid move,
  // which the check also accepts; a rejection there would be a bug here.
  std::vector<RoutePoint> smooth{a};
  std::size_t anchor = 0;
  while (anchor + 1 < grid_path.size()) {
    std::size_t reach = anchor + 1;
    if (!SegmentIsReachable(grid_path[anchor], grid_path[reach]))
      throw std::logic_error("a grid move of the A* path failed the line-of-sight check");
    while (reach + 1 < grid_path.size() && SegmentIsReachable(grid_path[anchor], grid_path[reach + 1])) ++reach;
    if (!SamePoint(smooth.back(), grid_path[reach])) smooth.push_back(grid_path[reach]);
    anchor = reach;
  }
  return smooth;
}

bool FreeSpaceRouteOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& message) {
    if (error != nullptr) *error = message;
    return false;
  };
  if (!(robot_radius_m > 0.0 && robot_radius_m <= 10.0)) return fail("robot_radius_m must be in (0, 10] m");
  if (waypoint_count < 2 || waypoint_count > 1000000) return fail("waypoint_count must be in [2, 10^6]");
  return true;
}

RoutePoint DrawRouteWaypoint(const ReachableFreeSpace& space, std::uint64_t seed, std::uint64_t index) {
  RandomStream stream(seed, StreamPurpose::kSimulation, index, 0);
  return space.DrawCellCentre(stream);
}

FreeSpaceRoute PlanFreeSpaceRoute(const ReachableFreeSpace& space, int waypoint_count, std::uint64_t seed) {
  if (waypoint_count < 2) throw std::invalid_argument("a route needs at least 2 waypoints");
  FreeSpaceRoute route;
  for (int i = 0; i < waypoint_count; ++i) {
    const RoutePoint w = DrawRouteWaypoint(space, seed, static_cast<std::uint64_t>(i));
    if (route.waypoints.empty() || !SamePoint(route.waypoints.back(), w)) route.waypoints.push_back(w);
  }
  if (route.waypoints.size() < 2)
    throw std::invalid_argument("fewer than 2 reachable waypoints: all " + std::to_string(waypoint_count) +
                                " draws fell on the same cell (the robot can reach " +
                                std::to_string(space.reachable_cells().size()) +
                                " cell(s)); use a roomier map, a "
                                "smaller robot radius or more waypoints");
  route.polyline.push_back(route.waypoints.front());
  for (std::size_t i = 1; i < route.waypoints.size(); ++i) {
    const std::vector<RoutePoint> leg = space.PlanPath(route.waypoints[i - 1], route.waypoints[i]);
    route.polyline.insert(route.polyline.end(), leg.begin() + 1, leg.end());
  }
  return route;
}

FreeSpaceRoute PlanFreeSpaceRoute(const OccupancyGrid& grid, const FreeSpaceRouteOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument("route options: " + error);
  const ReachableFreeSpace space(grid, options.robot_radius_m);
  return PlanFreeSpaceRoute(space, options.waypoint_count, options.seed);
}

}  // namespace rc
