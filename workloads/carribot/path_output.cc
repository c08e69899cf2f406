#include "workloads/carribot/path_output.h"

#include "common/angles.h"
#include "traces/csv_table.h"

namespace rc {

void WritePathCsv(const std::string& path, const PlanResult& result, double resolution_m, int heading_count) {
  CsvTable table(path, {"step", "x_cell", "y_cell", "heading", "x_m", "y_m", "theta_rad", "cost_cells", "cost_m"});
  for (std::size_t i = 0; i < result.path.size(); ++i) {
    const PathState& s = result.path[i];
    const bool has_heading = heading_count > 0 && s.heading != kAnyHeading;
    table.AddRow({i, s.x, s.y, has_heading ? CsvCell(s.heading) : CsvCell::Empty(), (s.x + 0.5) * resolution_m,
                  (s.y + 0.5) * resolution_m,
                  has_heading ? CsvCell(WrapAngle(2.0 * kPi * s.heading / heading_count)) : CsvCell::Empty(),
                  s.cost_cells, s.cost_cells * resolution_m});
  }
  table.Commit();
}

}  // namespace rc
