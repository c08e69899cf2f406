#pragma once
// Reader for MovingAI scenario files (.scen, movingai.com benchmarks):
//   version 1
//   bucket <TAB> map <TAB> W <TAB> H <TAB> sx <TAB> sy <TAB> gx <TAB> gy <TAB> optimal_length
// Coordinates are cells of the map named on the line: x = column, y = line of
// the map body, exactly as LoadMovingAiMap indexes its grid. The optimal
// length is in cells, with cost 1 straight, sqrt(2) diagonal and no corner
// cutting (../shared/data/README.md).
//
// Strict: every problem is an InputError naming the file, the 1-based line and
// the field (bucket, map, width, height, start_x, start_y, goal_x, goal_y,
// optimal_length), so a truncated or hand-edited file is never half-read.
#include <string>
#include <vector>

#include "maps/occupancy_grid.h"

namespace rc {

struct MovingAiScenario {
  long line = 0;  // 1-based line in the .scen file, for later error messages
  int bucket = 0;
  std::string map_name;
  int map_width = 0;   // cells
  int map_height = 0;  // cells
  int start_x = 0;
  int start_y = 0;
  int goal_x = 0;
  int goal_y = 0;
  double optimal_length = 0.0;  // cells
};

struct MovingAiScenarioFile {
  std::string path;
  std::vector<MovingAiScenario> scenarios;  // in file order; may be empty
};

// Throws InputError for a file that cannot be opened, a first line other than
// "version 1" (or "version 1.0"), a line with too few fields (naming the
// first missing one) or too many, a non-integer or out-of-range value, a
// start or goal outside the W x H the line declares, and a negative or
// non-finite optimal length. Blank lines are skipped.
MovingAiScenarioFile ReadMovingAiScenarios(const std::string& path);

// Throws InputError(path, line, "width" or "height", ...) for the first
// scenario whose declared map size differs from the grid's. Together with the
// reader's own bounds check this puts every start and goal inside the grid.
void CheckScenariosMatchMap(const MovingAiScenarioFile& file, const OccupancyGrid& grid);

}  // namespace rc
