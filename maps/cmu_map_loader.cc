#include "maps/cmu_map_loader.h"

#include <cmath>
#include <fstream>
#include <map>

#include "common/text_fields.h"
#include "maps/grid_size_limits.h"
#include "maps/probability_rows.h"

namespace rc {

OccupancyGrid LoadCmuMap(const std::string& path, const CmuMapOptions& options, CellClassCounts* counts) {
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "", "cannot open map file");
  LineReader reader(in, path);
  std::string line;
  struct SpecValue {
    double value = 0.0;
    long line = 0;
  };
  std::map<std::string, SpecValue> spec;  // robot_specifications->key value
  long size_x = -1, size_y = -1, size_line = 0;
  const std::string kSpecPrefix = "robot_specifications->";
  while (reader.Next(line)) {
    auto fields = SplitFields(line);
    if (fields.empty()) continue;
    if (fields[0].rfind(kSpecPrefix, 0) == 0) {
      std::string key(fields[0].substr(kSpecPrefix.size()));
      if (fields.size() != 2) reader.Fail(key, "expected one value after the key");
      spec[key] = {reader.ParseDouble(fields[1], key), reader.line_number()};
      continue;
    }
    if (fields[0] == "global_map[0]:") {
      if (fields.size() != 3) reader.Fail("global_map[0]", "expected 'global_map[0]: size_x size_y'");
      size_x = reader.ParseInt(fields[1], "global_map size_x", 1, kMaxMapCellsPerSide);
      size_y = reader.ParseInt(fields[2], "global_map size_y", 1, kMaxMapCellsPerSide);
      size_line = reader.line_number();
      break;
    }
    reader.Fail("header", "unexpected line before 'global_map[0]:' (is this a CMU .dat map?)");
  }
  if (size_x < 0) throw InputError(path, reader.line_number(), "global_map[0]", "missing map size line");
  auto resolution_it = spec.find("resolution");
  if (resolution_it == spec.end()) throw InputError(path, 0, "robot_specifications->resolution", "missing");
  const double resolution_cm = resolution_it->second.value;
  if (!(resolution_cm > 0.0))
    throw InputError(path, resolution_it->second.line, "robot_specifications->resolution", "must be positive (cm)");
  // The declared extent (cm) must agree with cells x resolution.
  for (const char* axis : {"x", "y"}) {
    auto it = spec.find(std::string("global_mapsize_") + axis);
    if (it == spec.end()) continue;
    const long cells = axis[0] == 'x' ? size_x : size_y;
    if (std::abs(it->second.value - cells * resolution_cm) > 0.5 * resolution_cm)
      throw InputError(path, it->second.line, std::string("robot_specifications->global_mapsize_") + axis,
                       "extent " + std::to_string(it->second.value) + " cm disagrees with " + std::to_string(cells) +
                           " cells of " + std::to_string(resolution_cm) + " cm");
  }

  CheckMapSize(path, size_line, "global_map[0]", size_x, size_y);
  OccupancyGrid grid(static_cast<int>(size_x), static_cast<int>(size_y), resolution_cm / 100.0, CellState::kUnknown);
  ReadProbabilityRows(reader, options.convention, options.thresholds, &grid, counts);
  RequireNoTrailingData(reader);
  return grid;
}

}  // namespace rc
