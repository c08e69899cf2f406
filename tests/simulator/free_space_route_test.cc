#include "workloads/delibot/free_space_route.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "simulator/room_map.h"

namespace rc {
namespace {

using test::ClearanceToBlocking;
using test::MakeRoomWithDoor;

// Samples every segment of the polyline at most `step_m` apart (end points
// included) and returns the smallest exact clearance seen.
double MinClearanceAlong(const OccupancyGrid& grid, const std::vector<RoutePoint>& polyline, double step_m) {
  double worst = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < polyline.size(); ++i) {
    const RoutePoint& a = polyline[i];
    const RoutePoint& b = polyline[i + 1];
    const double length = std::hypot(b.x_m - a.x_m, b.y_m - a.y_m);
    const int samples = static_cast<int>(std::ceil(length / step_m));
    for (int k = 0; k <= samples; ++k) {
      const double t = samples == 0 ? 0.0 : static_cast<double>(k) / samples;
      const double x = a.x_m + t * (b.x_m - a.x_m), y = a.y_m + t * (b.y_m - a.y_m);
      worst = std::min(worst, ClearanceToBlocking(grid, x, y, 1.0));
    }
  }
  return worst;
}

bool SamePoint(const RoutePoint& a, const RoutePoint& b) { return a.x_m == b.x_m && a.y_m == b.y_m; }

TEST(FreeSpaceRoute, RouteIsCollisionFreeForTheDiscAtEverySample) {
  const OccupancyGrid grid = MakeRoomWithDoor();
  bool some_route_uses_the_door = false;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    FreeSpaceRouteOptions options;
    options.robot_radius_m = 0.2;
    options.waypoint_count = 8;
    options.seed = seed;
    const FreeSpaceRoute route = PlanFreeSpaceRoute(grid, options);
    ASSERT_GE(route.waypoints.size(), 2u);
    ASSERT_GE(route.polyline.size(), 2u);
    EXPECT_GE(MinClearanceAlong(grid, route.polyline, 0.01), options.robot_radius_m - 1e-9) << "seed " << seed;
    // The polyline starts and ends at the waypoints and visits each in order.
    EXPECT_TRUE(SamePoint(route.polyline.front(), route.waypoints.front()));
    EXPECT_TRUE(SamePoint(route.polyline.back(), route.waypoints.back()));
    std::size_t next = 0;
    for (const RoutePoint& p : route.polyline)
      if (next < route.waypoints.size() && SamePoint(p, route.waypoints[next])) ++next;
    EXPECT_EQ(next, route.waypoints.size()) << "seed " << seed;
    for (std::size_t i = 1; i < route.polyline.size(); ++i)
      EXPECT_FALSE(SamePoint(route.polyline[i - 1], route.polyline[i]));
    for (std::size_t i = 1; i < route.waypoints.size(); ++i)
      if ((route.waypoints[i - 1].x_m < test::kWallX0) != (route.waypoints[i].x_m < test::kWallX0))
        some_route_uses_the_door = true;
  }
  // Both rooms form one reachable component, so some leg crosses the door.
  EXPECT_TRUE(some_route_uses_the_door);
}

TEST(FreeSpaceRoute, StraightLineOfSightGivesASingleSegment) {
  const OccupancyGrid grid = MakeRoomWithDoor();
  const ReachableFreeSpace space(grid, 0.2);
  const RoutePoint a{1.025, 1.025}, b{4.025, 3.075};
  const std::vector<RoutePoint> path = space.PlanPath(a, b);
  ASSERT_EQ(path.size(), 2u) << "string pulling should remove the grid staircase";
  EXPECT_TRUE(SamePoint(path[0], a));
  EXPECT_TRUE(SamePoint(path[1], b));
  EXPECT_EQ(space.PlanPath(a, a).size(), 1u);
}

TEST(FreeSpaceRoute, PathBetweenRoomsGoesThroughTheDoorAndIsShort) {
  const OccupancyGrid grid = MakeRoomWithDoor();
  const double radius = 0.2;
  const ReachableFreeSpace space(grid, radius);
  // Both points low in their rooms (b left of the unknown patch): the path
  // must climb to the door and back down.
  const RoutePoint a{2.025, 1.025}, b{6.025, 1.025};
  const std::vector<RoutePoint> path = space.PlanPath(a, b);
  EXPECT_GE(MinClearanceAlong(grid, path, 0.01), radius - 1e-9);
  EXPECT_LE(path.size(), 6u) << "a smoothed path needs about one vertex per door edge";
  double length = 0.0;
  bool crossed_in_door = false;
  for (std::size_t i = 1; i < path.size(); ++i) {
    const RoutePoint& p = path[i - 1];
    const RoutePoint& q = path[i];
    length += std::hypot(q.x_m - p.x_m, q.y_m - p.y_m);
    const double x_mid = 0.5 * (test::kWallX0 + test::kWallX1);
    if ((p.x_m - x_mid) * (q.x_m - x_mid) < 0.0) {
      const double y = p.y_m + (x_mid - p.x_m) / (q.x_m - p.x_m) * (q.y_m - p.y_m);
      crossed_in_door = y > test::kDoorY0 + radius && y < test::kDoorY1 - radius;
    }
  }
  EXPECT_TRUE(crossed_in_door);
  // Shortest possible for the disc: straight to the door's lowest safe point
  // (y = 3.5 + 0.2 m), through the 0.1 m wall, and straight on to b: 6.93 m.
  // The planner keeps radius + sqrt(2) * resolution from wall cell centres,
  // so it rounds the door's corners a little wider; no detours beyond that.
  EXPECT_GT(length, 6.93);
  EXPECT_LT(length, 7.4);
}

TEST(FreeSpaceRoute, SegmentCheckRejectsWallsAndAcceptsTheDoor) {
  const OccupancyGrid grid = MakeRoomWithDoor();
  const ReachableFreeSpace space(grid, 0.2);
  EXPECT_FALSE(space.SegmentIsReachable({3.0, 1.0}, {7.0, 1.0}));    // through the wall
  EXPECT_TRUE(space.SegmentIsReachable({3.0, 4.0}, {7.0, 4.0}));     // through the door
  EXPECT_FALSE(space.SegmentIsReachable({3.0, 3.65}, {7.0, 3.65}));  // door, but too close to its edge
  EXPECT_FALSE(space.IsReachablePoint({0.1, 4.0}));                  // touching the outer wall
  EXPECT_FALSE(space.IsReachablePoint({-1.0, 4.0}));
}

TEST(FreeSpaceRoute, SameSeedSameRouteOtherSeedOtherRoute) {
  const OccupancyGrid grid = MakeRoomWithDoor();
  FreeSpaceRouteOptions options;
  const FreeSpaceRoute a = PlanFreeSpaceRoute(grid, options);
  const FreeSpaceRoute b = PlanFreeSpaceRoute(grid, options);
  ASSERT_EQ(a.polyline.size(), b.polyline.size());
  for (std::size_t i = 0; i < a.polyline.size(); ++i) EXPECT_TRUE(SamePoint(a.polyline[i], b.polyline[i]));
  options.seed = 2;
  const FreeSpaceRoute c = PlanFreeSpaceRoute(grid, options);
  EXPECT_FALSE(SamePoint(a.waypoints[0], c.waypoints[0]) && SamePoint(a.waypoints[1], c.waypoints[1]));
}

std::string ErrorOf(const OccupancyGrid& grid, const FreeSpaceRouteOptions& options) {
  try {
    PlanFreeSpaceRoute(grid, options);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no error";
}

TEST(FreeSpaceRoute, MapWithoutFreeCellIsAnError) {
  const OccupancyGrid grid(40, 40, 0.05, CellState::kOccupied);
  EXPECT_NE(ErrorOf(grid, {}).find("no free cell"), std::string::npos) << ErrorOf(grid, {});
}

TEST(FreeSpaceRoute, FreeSpaceNarrowerThanTheRobotIsAnError) {
  // A 0.3 m wide strip: a 0.2 m radius robot needs 0.4 m plus margin.
  const OccupancyGrid grid(60, 6, 0.05, CellState::kFree);
  const std::string error = ErrorOf(grid, {});
  EXPECT_NE(error.find("too narrow"), std::string::npos) << error;
  // The same strip is wide enough for a small robot.
  FreeSpaceRouteOptions small;
  small.robot_radius_m = 0.05;
  EXPECT_NO_THROW(PlanFreeSpaceRoute(grid, small));
}

TEST(FreeSpaceRoute, SingleReachableCellGivesFewerThanTwoWaypoints) {
  // 11 x 11 free cells of 0.05 m: only the centre cell is 0.3 m from the
  // border cells' centres; its neighbours are 0.25 m, below the 0.2 m radius
  // plus sqrt(2) * 0.05 m the planner needs.
  const OccupancyGrid grid(11, 11, 0.05, CellState::kFree);
  const ReachableFreeSpace space(grid, 0.2);
  EXPECT_EQ(space.reachable_cells().size(), 1u);
  const std::string error = ErrorOf(grid, {});
  EXPECT_NE(error.find("fewer than 2 reachable waypoints"), std::string::npos) << error;
}

TEST(FreeSpaceRoute, InvalidOptionsAreRejected) {
  const OccupancyGrid grid = MakeRoomWithDoor();
  FreeSpaceRouteOptions options;
  options.waypoint_count = 1;
  std::string error;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("waypoint_count"), std::string::npos);
  EXPECT_THROW(PlanFreeSpaceRoute(grid, options), std::invalid_argument);
  options = {};
  options.robot_radius_m = -0.1;
  EXPECT_THROW(PlanFreeSpaceRoute(grid, options), std::invalid_argument);
}

}  // namespace
}  // namespace rc
