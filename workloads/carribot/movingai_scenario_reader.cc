#include "workloads/carribot/movingai_scenario_reader.h"

#include <array>
#include <fstream>
#include <string_view>

#include "common/text_fields.h"
#include "maps/grid_size_limits.h"

namespace rc {
namespace {

constexpr std::array<const char*, 9> kFieldNames = {"bucket",  "map",    "width",  "height",        "start_x",
                                                    "start_y", "goal_x", "goal_y", "optimal_length"};

// The format is tab separated; a map name could in principle hold spaces, so
// spaces are not separators. Surrounding spaces of a field are trimmed.
std::vector<std::string_view> SplitTabs(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t tab = line.find('\t', start);
    std::string_view field = line.substr(start, tab == std::string_view::npos ? tab : tab - start);
    while (!field.empty() && field.front() == ' ') field.remove_prefix(1);
    while (!field.empty() && field.back() == ' ') field.remove_suffix(1);
    fields.push_back(field);
    if (tab == std::string_view::npos) return fields;
    start = tab + 1;
  }
}

bool IsBlank(const std::string& line) { return line.find_first_not_of(" \t") == std::string::npos; }

void ReadVersion(LineReader& reader) {
  std::string line;
  while (reader.Next(line)) {
    if (IsBlank(line)) continue;
    const auto fields = SplitFields(line);
    if (fields.size() != 2 || fields[0] != "version")
      reader.Fail("version", "expected 'version 1' as the first line, got '" + line + "'");
    if (fields[1] != "1" && fields[1] != "1.0")
      reader.Fail("version", "version '" + std::string(fields[1]) + "' is not supported (only version 1)");
    return;
  }
  throw InputError(reader.file(), reader.line_number() + 1, "version",
                   "file is empty; expected 'version 1' as the first line");
}

MovingAiScenario ParseScenarioLine(const LineReader& reader, const std::string& line) {
  const auto fields = SplitTabs(line);
  if (fields.size() < kFieldNames.size()) {
    std::string hint;
    if (fields.size() == 1 && line.find(' ') != std::string::npos)
      hint = " (fields must be separated by tabs, not spaces)";
    reader.Fail(kFieldNames[fields.size()], "line ends after " + std::to_string(fields.size()) + " of " +
                                                std::to_string(kFieldNames.size()) + " fields" + hint);
  }
  if (fields.size() > kFieldNames.size())
    reader.Fail("optimal_length", "line has " + std::to_string(fields.size()) + " fields, expected " +
                                      std::to_string(kFieldNames.size()));
  MovingAiScenario s;
  s.line = reader.line_number();
  s.bucket = static_cast<int>(reader.ParseInt(fields[0], kFieldNames[0], 0, 1000000000L));
  if (fields[1].empty()) reader.Fail(kFieldNames[1], "empty map name");
  s.map_name = std::string(fields[1]);
  s.map_width = static_cast<int>(reader.ParseInt(fields[2], kFieldNames[2], 1, kMaxMapCellsPerSide));
  s.map_height = static_cast<int>(reader.ParseInt(fields[3], kFieldNames[3], 1, kMaxMapCellsPerSide));
  s.start_x = static_cast<int>(reader.ParseInt(fields[4], kFieldNames[4], 0, s.map_width - 1));
  s.start_y = static_cast<int>(reader.ParseInt(fields[5], kFieldNames[5], 0, s.map_height - 1));
  s.goal_x = static_cast<int>(reader.ParseInt(fields[6], kFieldNames[6], 0, s.map_width - 1));
  s.goal_y = static_cast<int>(reader.ParseInt(fields[7], kFieldNames[7], 0, s.map_height - 1));
  s.optimal_length = reader.ParseDouble(fields[8], kFieldNames[8]);
  if (s.optimal_length < 0.0) reader.Fail(kFieldNames[8], "negative optimal length");
  return s;
}

}  // namespace

MovingAiScenarioFile ReadMovingAiScenarios(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "", "cannot open scenario file");
  LineReader reader(in, path);
  ReadVersion(reader);
  MovingAiScenarioFile file;
  file.path = path;
  std::string line;
  while (reader.Next(line)) {
    if (IsBlank(line)) continue;
    file.scenarios.push_back(ParseScenarioLine(reader, line));
  }
  return file;
}

void CheckScenariosMatchMap(const MovingAiScenarioFile& file, const OccupancyGrid& grid) {
  for (const MovingAiScenario& s : file.scenarios) {
    if (s.map_width != grid.size_x())
      throw InputError(file.path, s.line, "width",
                       "scenario map width " + std::to_string(s.map_width) + " differs from the map's " +
                           std::to_string(grid.size_x()) + " columns (scenario for another map?)");
    if (s.map_height != grid.size_y())
      throw InputError(file.path, s.line, "height",
                       "scenario map height " + std::to_string(s.map_height) + " differs from the map's " +
                           std::to_string(grid.size_y()) + " lines (scenario for another map?)");
  }
}

}  // namespace rc
