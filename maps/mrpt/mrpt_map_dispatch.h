#pragma once
// LoadMap plus MRPT's .gridmap and .simplemap. Reading them needs MRPT, and
// rc_maps (layer 0, linked by every target) must not, so the formats are
// registered here, one level up, and the command line calls this instead of
// LoadMap.
//
//   "gridmap"    .gridmap, .gridmap.gz      (mrpt_map_loader.h)
//   "simplemap"  .simplemap, .simplemap.gz  resolution_m sets the cell size
//                                           (default 0.06 m)
// Every other format and extension goes to LoadMap unchanged. As in LoadMap,
// an option that does not apply to the format is a UsageError.
#include <string>

#include "maps/map_loader.h"

namespace rc {

struct LoadedMapWithOrigin {
  LoadedMap map;
  // Where the map frame's origin sits in the file's world frame (MRPT's
  // x_min, y_min; a ROS map's origin); zero when the format has no world frame.
  double origin_x_m = 0.0;
  double origin_y_m = 0.0;
};

LoadedMapWithOrigin LoadMapWithMrpt(const std::string& path, const MapLoadOptions& options = {});

}  // namespace rc
