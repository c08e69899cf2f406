#pragma once
// Loader for plain images (PNG, PNM, JPEG or BMP: image_signature.h) used as maps without a YAML:
// the image's pixels are classified with ROS map_server's trinary rule and
// orientation (image_occupancy.h): p = (255 - v) / 255 (v / 255 with
// negate); occupied if p > occupied_thresh, free if p < free_thresh, unknown
// otherwise; image row 0 is the largest y. The scale comes from the caller.
// JPEG's lossy compression blurs wall edges into the unknown band; prefer a
// lossless format.
#include <string>

#include "maps/image_occupancy.h"
#include "maps/occupancy_grid.h"

namespace rc {

struct ImageMapOptions {
  double resolution_m = 0.0;   // m per cell; required, > 0
  PixelThresholds thresholds;  // map_server defaults 0.65 / 0.196, no negate
};

// Throws UsageError for a missing or non-positive resolution or invalid
// thresholds (they come from the command line, not the file), and
// InputError naming the image for a missing or undecodable image.
// Adds each cell's class to *counts when given.
OccupancyGrid LoadImageMap(const std::string& path, const ImageMapOptions& options, CellClassCounts* counts = nullptr);

}  // namespace rc
