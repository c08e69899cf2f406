#include "maps/rowild_map_loader.h"

#include <fstream>

#include "common/text_fields.h"
#include "maps/grid_size_limits.h"
#include "maps/probability_rows.h"

namespace rc {
namespace {

// Largest header number accepted (cm): 100 km, beyond any building.
constexpr long kMaxHeaderCm = 10000000;

struct HeaderValue {
  long value = 0;
  long line = 0;
};

// Reads the next non-blank line, which must be "<key> <integer>".
// (RoWild's stream extraction skips blank lines inside the header too.)
HeaderValue ReadHeaderLine(LineReader& reader, const std::string& key) {
  std::string line;
  while (reader.Next(line)) {
    const auto fields = SplitFields(line);
    if (fields.empty()) continue;
    if (fields[0] != key)
      reader.Fail(key, "expected '" + key + " <integer cm>' here, found '" + std::string(fields[0]) +
                           "' (RoWild header order: mapsize_x, mapsize_y, resolution)");
    if (fields.size() != 2) reader.Fail(key, "expected exactly one integer after the key");
    return {reader.ParseInt(fields[1], key, 1, kMaxHeaderCm), reader.line_number()};
  }
  throw InputError(reader.file(), reader.line_number() + 1, key, "file ends before the '" + key + "' header line");
}

// Number of cells along one axis; the extent must be a whole number of cells.
long CellsAlong(const std::string& file, const HeaderValue& extent, const std::string& key, long resolution_cm) {
  if (extent.value % resolution_cm != 0)
    throw InputError(file, extent.line, key,
                     "extent " + std::to_string(extent.value) + " cm is not a whole number of " +
                         std::to_string(resolution_cm) + " cm cells");
  return extent.value / resolution_cm;
}

}  // namespace

OccupancyGrid LoadRowildMap(const std::string& path, const RowildMapOptions& options, CellClassCounts* counts) {
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "", "cannot open map file");
  LineReader reader(in, path);
  const HeaderValue extent_x = ReadHeaderLine(reader, "mapsize_x");
  const HeaderValue extent_y = ReadHeaderLine(reader, "mapsize_y");
  const HeaderValue resolution = ReadHeaderLine(reader, "resolution");
  const long size_x = CellsAlong(path, extent_x, "mapsize_x", resolution.value);
  const long size_y = CellsAlong(path, extent_y, "mapsize_y", resolution.value);
  CheckMapSize(path, extent_x.line, "mapsize_x", size_x, size_y);

  OccupancyGrid grid(static_cast<int>(size_x), static_cast<int>(size_y), static_cast<double>(resolution.value) / 100.0,
                     CellState::kUnknown);
  ReadProbabilityRows(reader, options.convention, options.thresholds, &grid, counts);
  RequireNoTrailingData(reader);
  return grid;
}

}  // namespace rc
