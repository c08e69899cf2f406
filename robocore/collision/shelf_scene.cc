#include "robocore/collision/shelf_scene.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/random_stream.h"

namespace rc {
namespace {

Aabbd FromCorners(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  return Aabbd{0.5 * (lo + hi), 0.5 * (hi - lo)};
}

void AddShelf(const ShelfSceneOptions& o, double sign, std::uint64_t shelf_index, std::vector<Aabbd>& boxes) {
  const double t = o.panel_thickness_m;
  const double x0 = o.front_x_m, x1 = o.front_x_m + o.depth_m;
  const double y0 = -0.5 * o.width_m, y1 = 0.5 * o.width_m;
  std::vector<Aabbd> shelf;
  shelf.push_back(FromCorners({x1 - t, y0, 0}, {x1, y1, o.height_m}));  // back
  for (int c = 0; c <= o.columns; ++c) {                                // sides and dividers
    const double y = y0 + (y1 - y0) * c / o.columns;
    const double ylo = std::clamp(y - 0.5 * t, y0, y1 - t);
    shelf.push_back(FromCorners({x0, ylo, 0}, {x1 - t, ylo + t, o.height_m}));
  }
  std::vector<double> board_top;
  for (int r = 0; r <= o.rows; ++r) {  // boards, bottom one on the floor
    const double z = o.height_m * r / o.rows;
    const double zlo = std::clamp(z - 0.5 * t, 0.0, o.height_m - t);
    shelf.push_back(FromCorners({x0, y0, zlo}, {x1 - t, y1, zlo + t}));
    board_top.push_back(zlo + t);
  }
  RandomStream rng(o.seed, StreamPurpose::kMapGeneration, shelf_index, 0);
  for (int r = 0; r < o.rows; ++r)
    for (int c = 0; c < o.columns; ++c)
      for (int k = 0; k < o.objects_per_cubby; ++k) {
        const double cy0 = y0 + (y1 - y0) * c / o.columns + 0.5 * t;
        const double cy1 = y0 + (y1 - y0) * (c + 1) / o.columns - 0.5 * t;
        Eigen::Vector3d half;
        for (int j = 0; j < 3; ++j) half[j] = rng.Uniform(o.object_half_min_m, o.object_half_max_m);
        half[0] = std::min(half[0], 0.5 * (x1 - t - x0));
        half[1] = std::min(half[1], 0.5 * (cy1 - cy0));
        const double cubby_top = board_top[r + 1] - t;
        half[2] = std::min(half[2], 0.5 * (cubby_top - board_top[r]));
        Aabbd object;
        object.half = half;
        object.centre = {rng.Uniform(x0 + half[0], x1 - t - half[0]), rng.Uniform(cy0 + half[1], cy1 - half[1]),
                         board_top[r] + half[2]};  // resting on the board: touching it
        shelf.push_back(object);
      }
  for (Aabbd& b : shelf) {
    b.centre[0] *= sign;
    boxes.push_back(b);
  }
}

}  // namespace

bool ShelfSceneOptions::IsValid(std::string* error) const {
  auto fail = [&](const char* why) {
    if (error) *error = why;
    return false;
  };
  if (!(depth_m > 0 && width_m > 0 && height_m > 0 && std::isfinite(front_x_m)))
    return fail("depth, width and height must be > 0 and front_x finite");
  if (rows < 1 || columns < 1 || objects_per_cubby < 0) return fail("rows, columns >= 1, objects >= 0");
  if (!(panel_thickness_m > 0 && panel_thickness_m * (columns + 1) < width_m &&
        panel_thickness_m * (rows + 1) < height_m && panel_thickness_m < depth_m))
    return fail("panels must be thinner than the cubbies they make");
  if (!(object_half_min_m > 0 && object_half_max_m >= object_half_min_m))
    return fail("object half sizes need 0 < min <= max");
  if (mirrored_behind && front_x_m <= 0) return fail("a mirrored shelf needs front_x_m > 0");
  return true;
}

std::vector<Aabbd> MakeShelfScene(const ShelfSceneOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument("shelf scene: " + error);
  std::vector<Aabbd> boxes;
  AddShelf(options, 1.0, 0, boxes);
  if (options.mirrored_behind) AddShelf(options, -1.0, 1, boxes);
  return boxes;
}

}  // namespace rc
