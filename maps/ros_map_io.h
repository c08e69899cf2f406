#pragma once
// ROS map_server maps: a YAML file naming an image (PGM, PNG, ...).
//
//   image: office.pgm          path, relative to the YAML file's folder
//   resolution: 0.05           m per cell, > 0
//   origin: [-10.0, -7.5, 0.0] pose (x m, y m, yaw rad) of the image's
//                              bottom-left corner in the ROS world frame
//   occupied_thresh: 0.65      0 <= free_thresh < occupied_thresh <= 1
//   free_thresh: 0.196
//   negate: 0                  0/1 or false/true
//   mode: trinary              optional: trinary (default), scale or raw
//
// The pixel rules, the edge cases and the reduction of scale and raw mode to
// three states are in image_occupancy.h. All keys but mode are required, as
// in map_server; an unknown key is an error (a misspelt "mode" would
// otherwise silently fall back to trinary).
//
// Frames: grid cell (0, 0) is the bottom-left pixel, so the grid's frame is
// the ROS map origin frame; a grid point (gx, gy) is at
// origin + R(yaw) (gx, gy) in the ROS world frame. The loader returns the
// origin and leaves the transform to callers that need world coordinates.
#include <string>

#include "maps/cell_classes.h"
#include "maps/image_occupancy.h"
#include "maps/occupancy_grid.h"

namespace rc {

struct RosMapMetadata {
  std::string yaml_path;
  std::string image_path;  // as resolved against the YAML's folder
  double resolution_m = 0.0;
  double origin_x_m = 0.0;
  double origin_y_m = 0.0;
  double origin_yaw_rad = 0.0;
  ImageMapMode mode = ImageMapMode::kTrinary;
  PixelThresholds thresholds;  // includes negate
};

struct RosMap {
  OccupancyGrid grid;
  RosMapMetadata metadata;
  CellClassCounts cell_classes;
};

// Throws InputError naming the YAML file, the 1-based line (0 when the key is
// missing) and the key for: unreadable or malformed YAML, a missing, unknown
// or duplicated key, a non-numeric, NaN or infinite number, a non-positive
// resolution, an origin that is not three numbers, invalid thresholds,
// negate other than 0/1/false/true, an unknown mode, negate with raw mode,
// and an image file that does not exist. An image that exists but cannot be
// read (ReadImageGrid's errors, image_occupancy.h) raises InputError at the
// YAML's image key whose message carries the image's own error, e.g.
// "map.yaml:1: field 'image': map.pgm: field 'pixels': 20 of 400 values
// present". A directory given as either file is an InputError too.
RosMap LoadRosMap(const std::string& yaml_path);

struct RosMapSaveOptions {
  double origin_x_m = 0.0;
  double origin_y_m = 0.0;
  double origin_yaw_rad = 0.0;
  // File name (no folder) of the PGM written beside the YAML; empty: the
  // YAML's file name with its extension replaced by ".pgm".
  std::string image_file_name;
};

// Writes yaml_path and a binary PGM beside it with map_saver's convention:
// occupied 0, free 254, unknown 205, trinary mode, occupied_thresh 0.65,
// free_thresh 0.196, negate 0 (which load back to the same three states).
// Each file goes through AtomicFile; the image is committed first, so a YAML
// never names a missing image. Throws std::invalid_argument for a non-finite
// origin or an image name with a folder or characters YAML would need quoted,
// std::runtime_error on write failure.
void SaveRosMap(const OccupancyGrid& grid, const std::string& yaml_path, const RosMapSaveOptions& options = {});

}  // namespace rc
