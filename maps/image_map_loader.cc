#include "maps/image_map_loader.h"

#include <cmath>

#include "common/input_error.h"

namespace rc {

OccupancyGrid LoadImageMap(const std::string& path, const ImageMapOptions& options, CellClassCounts* counts) {
  if (!(options.resolution_m > 0.0) || !std::isfinite(options.resolution_m))
    throw UsageError("an image map needs a resolution: a positive number of metres per cell, got " +
                     std::to_string(options.resolution_m));
  std::string field, problem;
  if (!CheckPixelThresholds(options.thresholds, &field, &problem))
    throw UsageError("image map " + field + ": " + problem);
  return ReadImageGrid(path, options.resolution_m, options.thresholds, ImageMapMode::kTrinary, counts);
}

}  // namespace rc
