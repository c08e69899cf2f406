#pragma once
// A generated cubby-shelf scene for the real-OBB study (`rcbench collide
// --scene shelf`): the kind of scene the MPiNet / mpnet_master robot poses
// were planned in. A bookcase of rows x columns cubbies stands in front of
// the robot base (at the origin, z up), facing it; optionally a second one
// mirrored behind. Each cubby holds a few seeded "objects" resting on its
// board. Everything is an axis-aligned box, so the scene is exact (no
// voxels). Deterministic for a given seed.
#include <cstdint>
#include <string>
#include <vector>

#include "robocore/collision/aabb.h"

namespace rc {

struct ShelfSceneOptions {
  double front_x_m = 0.45;          // m, the shelf's open face (robot side)
  double depth_m = 0.35;            // m, front to back
  double width_m = 1.2;             // m, along y, centred on y = 0
  double height_m = 1.1;            // m, floor (z = 0) to top
  int rows = 3;                     // cubby rows
  int columns = 3;                  // cubby columns
  double panel_thickness_m = 0.02;  // m, boards, sides, dividers, back
  int objects_per_cubby = 2;        // boxes resting in each cubby
  double object_half_min_m = 0.02;  // m
  double object_half_max_m = 0.06;  // m
  bool mirrored_behind = true;      // a second shelf at x -> -x
  std::uint64_t seed = 1;
  bool IsValid(std::string* error) const;
};

// Throws std::invalid_argument for invalid options.
std::vector<Aabbd> MakeShelfScene(const ShelfSceneOptions& options = {});

}  // namespace rc
