#include "maps/probability_rows.h"

#include <string>

namespace rc {

void ReadProbabilityRows(LineReader& reader, ValueConvention convention, const ProbabilityThresholds& thresholds,
                         OccupancyGrid* grid, CellClassCounts* counts) {
  const long size_x = grid->size_x();
  const long size_y = grid->size_y();
  std::string line;
  for (long ix = 0; ix < size_x; ++ix) {
    const std::string row_field = "map row " + std::to_string(ix);
    if (!reader.Next(line))
      throw InputError(reader.file(), reader.line_number() + 1, row_field,
                       "file ends after " + std::to_string(ix) + " of " + std::to_string(size_x) + " rows");
    const auto fields = SplitFields(line);
    if (static_cast<long>(fields.size()) != size_y)
      reader.Fail(row_field, "has " + std::to_string(fields.size()) + " values, expected " + std::to_string(size_y));
    for (long iy = 0; iy < size_y; ++iy) {
      const std::string column_field = row_field + ", column " + std::to_string(iy);
      const double v = reader.ParseDouble(fields[iy], column_field);
      // -1 is the only negative value with a meaning; anything else below 0
      // or above 1 is corruption, not a probability.
      if (v > 1.0 || (v < 0.0 && v != -1.0))
        reader.Fail(column_field, "value " + std::string(fields[iy]) + " is neither a probability in [0, 1] nor -1");
      const CellClass c = ClassifyProbabilityValue(v, convention, thresholds);
      if (counts) counts->Add(c);
      grid->Set(static_cast<int>(ix), static_cast<int>(iy), StateOf(c));
    }
  }
}

void RequireNoTrailingData(LineReader& reader) {
  std::string line;
  while (reader.Next(line))
    if (!SplitFields(line).empty()) reader.Fail("trailing data", "extra content after the last map row");
}

}  // namespace rc
