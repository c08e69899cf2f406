#pragma once
// A PNG of a planned path on its map, for people: free cells white, occupied
// black, unknown grey; the path of cell centres in red, the start green, the
// goal magenta and, for a footprint robot, the rectangle's outline in blue at
// the start, the goal and evenly spaced states between.
//
// Orientation as every rcbench image: row 0 is the largest y (y up), so a
// MovingAI map appears mirrored top to bottom against its text file. Small
// maps are magnified by an integer factor (up to 8) so that the longer side
// has at least 512 pixels. Written through OpenCV's PNG encoder
// (maps/image_codec.h) and committed atomically.
#include <optional>
#include <string>

#include "maps/occupancy_grid.h"
#include "workloads/carribot/grid_planner.h"

namespace rc {

struct PathPlotOptions {
  std::optional<RectangleFootprint> footprint;  // unset: point robot
  int footprint_outlines = 24;                  // outlines drawn between start and goal (at most)
};

// Throws std::runtime_error when encoding or writing fails.
void WritePathPlot(const std::string& png_path, const OccupancyGrid& grid, const PlanResult& result,
                   const PathPlotOptions& options);

}  // namespace rc
