#pragma once
// One entry point for every 2D map format rcbench reads.
//
// Format by extension, unless MapLoadOptions::format names one:
//   .dat           "cmu" if the first line starts with robot_specifications->,
//                  "rowild" if it starts with mapsize_x (cmu_map_loader.h,
//                  rowild_map_loader.h)
//   .yaml .yml     "ros"       ROS map_server YAML + image (ros_map_io.h)
//   .map           "movingai"  MovingAI octile map (movingai_map_loader.h)
//   .png .pgm .jpg .jpeg
//                  "image"     plain image (image_map_loader.h)
// Options that do not apply to the chosen format are an error, not ignored,
// so that e.g. a value convention meant for wean.dat is never silently
// dropped when the file turns out to be a YAML.
#include <optional>
#include <string>

#include "maps/cell_classes.h"
#include "maps/image_occupancy.h"
#include "maps/occupancy_grid.h"
#include "maps/ros_map_io.h"
#include "maps/value_convention.h"

namespace rc {

struct MapLoadOptions {
  // "auto" (by extension and content), "cmu", "rowild", "ros", "movingai" or "image".
  std::string format = "auto";
  // cmu and rowild only; unset: P(free), the convention of the Wean data.
  std::optional<ValueConvention> convention;
  // movingai (unset: 1.0 m per cell) and image (required) only.
  std::optional<double> resolution_m;
  // Thresholds on P(occupied) for the formats whose cells hold a
  // probability: cmu, rowild, image (and MRPT's gridmap and simplemap,
  // mrpt_map_dispatch.h). Unset: ROS map_server's 0.65 / 0.196. A ROS YAML
  // declares its own, and MovingAI cells are terrain, so setting them for
  // those formats is a UsageError.
  std::optional<double> occupied_thresh;
  std::optional<double> free_thresh;
};

// The thresholds the options ask for (ROS's defaults where unset); throws
// UsageError unless 0 <= free < occupied <= 1.
ProbabilityThresholds ThresholdsFrom(const MapLoadOptions& options);

struct LoadedMap {
  OccupancyGrid grid;
  std::string format;  // the format actually used, as in MapLoadOptions::format
  // One line saying how stored values became free / occupied / unknown, for
  // the CLI to print (e.g. "values are P(free) ...").
  std::string value_convention;
  // Set for ROS maps: origin, image path, mode, thresholds.
  std::optional<RosMapMetadata> ros;
  // How many cells fell in each class, for the CLI's map line.
  CellClassCounts cell_classes;
};

// Throws UsageError for an unknown format name or an option that does not
// apply to the format; InputError (file, line, field) for an unknown
// extension, a .dat whose header is neither CMU nor RoWild, and every error
// of the individual loaders.
LoadedMap LoadMap(const std::string& path, const MapLoadOptions& options = {});

}  // namespace rc
