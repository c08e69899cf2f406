#include "maps/cmu_map_loader.h"

#include <cmath>
#include <fstream>
#include <map>

#include "common/text_fields.h"

namespace rc {
namespace {

constexpr long kMaxCellsPerSide = 100000;  // 10 km at 10 cm: far beyond any real map

}  // namespace

OccupancyGrid LoadCmuMap(const std::string& path, const CmuMapOptions& options) {
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "", "cannot open map file");
  LineReader reader(in, path);
  std::string line;
  std::map<std::string, double> spec;  // robot_specifications->key value
  long size_x = -1, size_y = -1;
  const std::string kSpecPrefix = "robot_specifications->";
  while (reader.Next(line)) {
    auto fields = SplitFields(line);
    if (fields.empty()) continue;
    if (fields[0].rfind(kSpecPrefix, 0) == 0) {
      std::string key(fields[0].substr(kSpecPrefix.size()));
      if (fields.size() != 2) reader.Fail(key, "expected one value after the key");
      spec[key] = reader.ParseDouble(fields[1], key);
      continue;
    }
    if (fields[0] == "global_map[0]:") {
      if (fields.size() != 3) reader.Fail("global_map[0]", "expected 'global_map[0]: size_x size_y'");
      size_x = reader.ParseInt(fields[1], "global_map size_x", 1, kMaxCellsPerSide);
      size_y = reader.ParseInt(fields[2], "global_map size_y", 1, kMaxCellsPerSide);
      break;
    }
    reader.Fail("header", "unexpected line before 'global_map[0]:' (is this a CMU .dat map?)");
  }
  if (size_x < 0) throw InputError(path, reader.line_number(), "global_map[0]", "missing map size line");
  auto resolution_it = spec.find("resolution");
  if (resolution_it == spec.end())
    throw InputError(path, 0, "robot_specifications->resolution", "missing");
  const double resolution_cm = resolution_it->second;
  if (!(resolution_cm > 0.0))
    throw InputError(path, 0, "robot_specifications->resolution", "must be positive (cm)");
  // The declared extent (cm) must agree with cells x resolution.
  for (const char* axis : {"x", "y"}) {
    auto it = spec.find(std::string("global_mapsize_") + axis);
    if (it == spec.end()) continue;
    const long cells = axis[0] == 'x' ? size_x : size_y;
    if (std::abs(it->second - cells * resolution_cm) > 0.5 * resolution_cm)
      throw InputError(path, 0, std::string("robot_specifications->global_mapsize_") + axis,
                       "extent " + std::to_string(it->second) + " cm disagrees with " +
                           std::to_string(cells) + " cells of " + std::to_string(resolution_cm) + " cm");
  }

  OccupancyGrid grid(static_cast<int>(size_x), static_cast<int>(size_y), resolution_cm / 100.0,
                     CellState::kUnknown);
  for (long ix = 0; ix < size_x; ++ix) {
    if (!reader.Next(line))
      throw InputError(path, reader.line_number() + 1, "map row " + std::to_string(ix),
                       "file ends after " + std::to_string(ix) + " of " + std::to_string(size_x) + " rows");
    auto fields = SplitFields(line);
    if (static_cast<long>(fields.size()) != size_y)
      reader.Fail("map row " + std::to_string(ix),
                  "has " + std::to_string(fields.size()) + " values, expected " + std::to_string(size_y));
    for (long iy = 0; iy < size_y; ++iy) {
      const double v = reader.ParseDouble(fields[iy], "column " + std::to_string(iy));
      if (v > 1.0 || (v < 0.0 && v != -1.0))
        reader.Fail("column " + std::to_string(iy),
                    "value " + std::to_string(v) + " is neither a probability in [0, 1] nor -1");
      grid.Set(static_cast<int>(ix), static_cast<int>(iy),
               ClassifyProbability(v, options.convention, options.thresholds));
    }
  }
  while (reader.Next(line))
    if (!SplitFields(line).empty()) reader.Fail("trailing data", "extra content after the last map row");
  return grid;
}

}  // namespace rc
