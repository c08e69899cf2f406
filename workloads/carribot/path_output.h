#pragma once
// Writes a planned path as a CSV table (traces/csv_table.h, committed
// atomically), one row per state from start to goal:
//   step, x_cell, y_cell, heading, x_m, y_m, theta_rad, cost_cells, cost_m
// x_m, y_m: the cell centre in the map frame ((ix + 0.5) * resolution);
// heading / theta_rad: heading index and angle (2 pi k / headings, from +x
// towards +y), empty for a point robot; cost: cumulative from the start.
#include <string>

#include "workloads/carribot/grid_planner.h"

namespace rc {

// heading_count = 0 for a point robot. Throws std::runtime_error when the
// file cannot be written.
void WritePathCsv(const std::string& path, const PlanResult& result, double resolution_m, int heading_count);

}  // namespace rc
