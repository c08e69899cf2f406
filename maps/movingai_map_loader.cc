#include "maps/movingai_map_loader.h"

#include <cmath>
#include <fstream>

#include <fmt/format.h>

#include "common/text_fields.h"
#include "maps/grid_size_limits.h"

namespace rc {
namespace {

bool IsTerrainCharacter(char c, CellState* state) {
  switch (c) {
    case '.':
    case 'G': *state = CellState::kFree; return true;
    case '@':
    case 'O':
    case 'T':
    case 'S':
    case 'W': *state = CellState::kOccupied; return true;
    default: return false;
  }
}

std::string Printable(char c) {
  if (c >= 0x21 && c <= 0x7e) return std::string("'") + c + "'";
  return fmt::format("{}0x{:02X})", c == ' ' ? "' ' (space, " : "byte (", static_cast<unsigned char>(c));
}

struct Header {
  long height = -1;
  long width = -1;
  bool has_type = false;
};

// Reads "type", "height", "width" in any order up to the "map" line.
Header ReadHeader(LineReader& reader) {
  Header h;
  std::string line;
  while (reader.Next(line)) {
    const auto fields = SplitFields(line);
    if (fields.empty()) continue;
    const std::string key(fields[0]);
    if (key == "map") {
      if (fields.size() != 1) reader.Fail("map", "expected the line 'map' alone");
      if (!h.has_type) reader.Fail("type", "missing 'type octile' before 'map'");
      if (h.height < 0) reader.Fail("height", "missing 'height H' before 'map'");
      if (h.width < 0) reader.Fail("width", "missing 'width W' before 'map'");
      return h;
    }
    if (fields.size() != 2) reader.Fail(key, "expected '" + key + " <value>'");
    if (key == "type") {
      if (h.has_type) reader.Fail(key, "appears twice");
      if (fields[1] != "octile")
        reader.Fail(key, "'" + std::string(fields[1]) + "' is not 'octile', the only MovingAI map type");
      h.has_type = true;
    } else if (key == "height" || key == "width") {
      long& value = key == "height" ? h.height : h.width;
      if (value >= 0) reader.Fail(key, "appears twice");
      value = reader.ParseInt(fields[1], key, 1, kMaxMapCellsPerSide);
    } else {
      reader.Fail("header",
                  "unknown header line '" + line + "' (is this a MovingAI .map? expected type, height, width, map)");
    }
  }
  throw InputError(reader.file(), reader.line_number() + 1, "map",
                   "file ends before the 'map' line that starts the grid");
}

}  // namespace

OccupancyGrid LoadMovingAiMap(const std::string& path, const MovingAiMapOptions& options) {
  if (!(options.resolution_m > 0.0) || !std::isfinite(options.resolution_m))
    throw UsageError("MovingAI map resolution must be a positive number of metres per cell, got " +
                     std::to_string(options.resolution_m));
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "", "cannot open map file");
  LineReader reader(in, path);
  const Header header = ReadHeader(reader);
  CheckMapSize(path, reader.line_number(), "map", header.width, header.height);

  OccupancyGrid grid(static_cast<int>(header.width), static_cast<int>(header.height), options.resolution_m,
                     CellState::kUnknown);
  std::string line;
  for (long y = 0; y < header.height; ++y) {
    const std::string row_field = "map row " + std::to_string(y);
    if (!reader.Next(line))
      throw InputError(path, reader.line_number() + 1, row_field,
                       "file ends after " + std::to_string(y) + " of " + std::to_string(header.height) +
                           " rows (height " + std::to_string(header.height) + ")");
    // Spaces or tabs after the last cell are an editor's residue, like the
    // '\r' of CRLF that LineReader drops; inside a row they stay an error.
    line.erase(line.find_last_not_of(" \t") + 1);
    if (static_cast<long>(line.size()) != header.width)
      reader.Fail(row_field,
                  "has " + std::to_string(line.size()) + " characters, expected width " + std::to_string(header.width));
    for (long x = 0; x < header.width; ++x) {
      CellState state;
      if (!IsTerrainCharacter(line[x], &state))
        reader.Fail(row_field + ", column " + std::to_string(x),
                    "unknown terrain character " + Printable(line[x]) + " (expected . G @ O T S W)");
      grid.Set(static_cast<int>(x), static_cast<int>(y), state);
    }
  }
  while (reader.Next(line))
    if (!SplitFields(line).empty())
      reader.Fail("trailing data", "content after the last of " + std::to_string(header.height) +
                                       " map rows (more rows than the height?)");
  return grid;
}

}  // namespace rc
