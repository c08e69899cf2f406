#pragma once
// RoWild MoveBot's obstacle file (shared data movebot/locobot_obs.txt): one
// cuboid per line, `roll, pitch, yaw, x, y, z, dimX, dimY, dimZ` (rad, m;
// FULL dimensions), comma separated; `#` lines and blank lines are skipped.
// Orientation: R = Rz(yaw) Ry(pitch) Rx(roll), the URDF convention RoWild's
// rpyxyzToH uses. Every bad value is an InputError naming file, line and
// field: a wrong field count (naming the first missing field, or "field 10"),
// a non-number (hexadecimal included), NaN or inf, a negative size. A file
// with no obstacle line at all (empty, or only comments) is an InputError
// too (line 0, field "obstacles"): planning in an empty scene would hide a
// wrong path. A directory is refused as "not a file" (LineReader), and a
// UTF-8 byte-order mark is skipped. A zero size is allowed (a wall of zero
// thickness, as aabb.h allows).
#include <istream>
#include <string>
#include <vector>

#include "robocore/collision/obb.h"

namespace rc {

struct Obstacle {
  Obbd box;       // world frame; half = dims / 2
  long line = 0;  // 1-based line in the file, for messages
};

std::vector<Obstacle> ReadObstacleFile(const std::string& path);
std::vector<Obstacle> ReadObstacleFile(std::istream& in, const std::string& file_name);

}  // namespace rc
