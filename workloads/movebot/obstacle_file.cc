#include "workloads/movebot/obstacle_file.h"

#include <fstream>

#include <Eigen/Geometry>

#include "common/input_error.h"
#include "common/text_fields.h"

namespace rc {

std::vector<Obstacle> ReadObstacleFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "", "cannot open the obstacle file");
  return ReadObstacleFile(in, path);
}

std::vector<Obstacle> ReadObstacleFile(std::istream& in, const std::string& file_name) {
  static const char* const kFields[9] = {"roll", "pitch", "yaw", "x", "y", "z", "dimX", "dimY", "dimZ"};
  LineReader reader(in, file_name);
  std::vector<Obstacle> out;
  std::string line;
  while (reader.Next(line)) {
    const std::size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    const auto fields = SplitFields(line, /*comma_separated=*/true);
    // A short line names its first missing field, a long one its first extra.
    if (fields.size() != 9)
      reader.Fail(fields.size() < 9 ? kFields[fields.size()] : "field 10",
                  "expected 9 comma-separated fields (roll, pitch, yaw, x, y, z, dimX, dimY, dimZ), found " +
                      std::to_string(fields.size()));
    double v[9];
    for (int k = 0; k < 9; ++k) v[k] = reader.ParseDouble(fields[k], kFields[k]);
    for (int k = 6; k < 9; ++k)
      if (v[k] < 0) reader.Fail(kFields[k], "a size must be >= 0 (full dimension, m)");
    Obstacle o;
    o.line = reader.line_number();
    o.box.centre = {v[3], v[4], v[5]};
    o.box.axes = (Eigen::AngleAxisd(v[2], Eigen::Vector3d::UnitZ()) *
                  Eigen::AngleAxisd(v[1], Eigen::Vector3d::UnitY()) * Eigen::AngleAxisd(v[0], Eigen::Vector3d::UnitX()))
                     .toRotationMatrix();
    o.box.half = Eigen::Vector3d(v[6], v[7], v[8]) / 2;
    out.push_back(o);
  }
  if (out.empty())
    throw InputError(file_name, 0, "obstacles",
                     "holds no obstacle (no 'roll, pitch, yaw, x, y, z, dimX, dimY, dimZ' line); an empty file is "
                     "more likely a mistake than an empty scene");
  return out;
}

}  // namespace rc
