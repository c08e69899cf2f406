#pragma once
// 2D ray casting kernels for Monte Carlo Localization (DeliBot).
//
// Each kernel answers one query (origin, angle, max range) with the range to
// the first cell that stops the ray, plus the number of nodes it fetched. The
// kernels are templates over a FetchVisitor so that a backend can record every
// memory access of a query (RangeLibc's access-trace hook) while the plain
// functional path compiles the hook away.
//
// A ray is stopped by an occupied cell, an unknown cell, or the map border
// (the outside counts as a wall), as in AMCL's map_calc_range.
//
// Methods, with their semantics, memory and precomputation:
//   march  Fixed step of one cell size along the ray (RoWild / RoboGPU
//          DeliBot semantics). Samples the point o + k*r*d for k = 0, 1, ...
//          and returns k*r for the first sample inside a stopping cell.
//          Can skip a cell corner the ray clips. No precomputation.
//          Nodes = samples taken (one 1-byte cell fetch each).
//   dda    Exact grid traversal (Amanatides & Woo): visits every cell the
//          ray crosses and returns the exact distance at which it enters the
//          first stopping cell. No precomputation. Nodes = cells visited.
//   rm     Ray marching on the distance field (RangeLibc's "rm"), made exact:
//          from any point of the current cell, every stopping cell is at
//          least d - sqrt(2)*r away (d = centre-to-centre distance), so the
//          ray jumps by that much minus half a cell of margin; close to
//          walls it falls back to single exact DDA steps. Its ranges equal
//          dda's. Precomputation: one distance field, 4 bytes per cell,
//          built in linear time. Nodes = distance-field fetches.
// Cell boundaries are always computed from the ray origin by formula (never
// accumulated), so dda and rm agree exactly.
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "maps/distance_field.h"
#include "maps/occupancy_grid.h"

namespace rc {

enum class RayCastMethod { kMarch, kDda, kRayMarching };

RayCastMethod ParseRayCastMethod(const std::string& name);  // "march" | "dda" | "rm"
std::string ToString(RayCastMethod m);

// What a node fetch reads, so a backend can price its bytes.
enum class FetchKind : std::uint8_t {
  kGridCell = 0,      // one CellState byte
  kDistanceCell = 1,  // one float of the distance field
  kTreeNode = 2,      // one flattened box-tree node (robocore/collision/flat_box_tree.h)
};

struct RayHit {
  float range_m = 0.0f;
  std::uint32_t nodes = 0;
};

// The scene a ray caster needs: the grid, and the distance field only for rm
// (DESIGN.md: "a distance field exists only when the chosen ray caster uses it").
class RayCastScene {
 public:
  RayCastScene(const OccupancyGrid& grid, RayCastMethod method);
  const OccupancyGrid& grid() const { return *grid_; }
  RayCastMethod method() const { return method_; }
  // Null unless method() == kRayMarching.
  const DistanceField* distance_field() const { return distance_field_.get(); }
  double build_seconds() const { return build_seconds_; }
  std::size_t precomputed_bytes() const;
  // dda and march (else empty): the grid's cells followed by kGatherPadding zero
  // bytes, so that a 4-byte gather at any cell's address stays inside
  // (ray_batch_lanes.h). Host-side only: no backend prices it.
  const std::vector<CellState>& gather_cells() const { return gather_cells_; }
  static constexpr std::size_t kGatherPadding = 3;

 private:
  const OccupancyGrid* grid_;
  RayCastMethod method_;
  std::shared_ptr<const DistanceField> distance_field_;
  std::vector<CellState> gather_cells_;
  double build_seconds_ = 0.0;
};

struct NoFetchVisitor {
  void Fetch(FetchKind, std::uint32_t /*index*/) {}
};

namespace ray_cast_detail {

// Per-axis traversal state computed from the origin by formula.
struct Axis {
  double origin = 0.0;   // m
  double dir = 0.0;      // unit-vector component
  double inv_dir = 0.0;  // 1 / dir (0 when dir is 0): a multiply per boundary, not a divide
  int step = 0;          // +1, -1 or 0
  double BoundaryTime(int cell, double r) const {
    // Time at which the ray leaves `cell` along this axis.
    if (step == 0) return std::numeric_limits<double>::infinity();
    const int boundary = step > 0 ? cell + 1 : cell;
    return (boundary * r - origin) * inv_dir;
  }
  double EntryTime(int cell, double r) const {
    if (step == 0) return -std::numeric_limits<double>::infinity();
    const int boundary = step > 0 ? cell : cell + 1;
    return (boundary * r - origin) * inv_dir;
  }
};

inline Axis MakeAxis(double origin, double dir) {
  Axis a;
  a.origin = origin;
  a.dir = dir;
  a.step = dir > 0.0 ? 1 : (dir < 0.0 ? -1 : 0);
  a.inv_dir = a.step == 0 ? 0.0 : 1.0 / dir;
  return a;
}

inline bool Stops(const OccupancyGrid& g, int ix, int iy) {
  return !g.Contains(ix, iy) || g.At(ix, iy) != CellState::kFree;
}

}  // namespace ray_cast_detail

template <typename Visitor>
RayHit CastMarch(const OccupancyGrid& g, double ox, double oy, double angle, double max_range, Visitor& visitor) {
  const double r = g.resolution_m();
  const double dx = std::cos(angle), dy = std::sin(angle);
  RayHit hit;
  const long steps = static_cast<long>(std::floor(max_range / r));
  for (long k = 0; k <= steps; ++k) {
    const double t = k * r;
    const int ix = static_cast<int>(std::floor((ox + t * dx) / r));
    const int iy = static_cast<int>(std::floor((oy + t * dy) / r));
    if (!g.Contains(ix, iy)) {
      hit.range_m = static_cast<float>(t);
      return hit;
    }
    visitor.Fetch(FetchKind::kGridCell, static_cast<std::uint32_t>(g.Index(ix, iy)));
    ++hit.nodes;
    if (g.At(ix, iy) != CellState::kFree) {
      hit.range_m = static_cast<float>(t);
      return hit;
    }
  }
  hit.range_m = static_cast<float>(max_range);
  return hit;
}

template <typename Visitor>
RayHit CastDda(const OccupancyGrid& g, double ox, double oy, double angle, double max_range, Visitor& visitor) {
  using namespace ray_cast_detail;
  const double r = g.resolution_m();
  const Axis ax = MakeAxis(ox, std::cos(angle));
  const Axis ay = MakeAxis(oy, std::sin(angle));
  int ix = static_cast<int>(std::floor(ox / r));
  int iy = static_cast<int>(std::floor(oy / r));
  RayHit hit;
  double t_enter = 0.0;
  while (true) {
    if (t_enter >= max_range) {
      hit.range_m = static_cast<float>(max_range);
      return hit;
    }
    if (!g.Contains(ix, iy)) {
      hit.range_m = static_cast<float>(t_enter);
      return hit;
    }
    visitor.Fetch(FetchKind::kGridCell, static_cast<std::uint32_t>(g.Index(ix, iy)));
    ++hit.nodes;
    if (g.At(ix, iy) != CellState::kFree) {
      hit.range_m = static_cast<float>(t_enter);
      return hit;
    }
    const double tx = ax.BoundaryTime(ix, r), ty = ay.BoundaryTime(iy, r);
    // Ties (the ray through a cell corner) step x first, then y: the corner
    // cell on the x side is visited, so a ray cannot slip between two
    // diagonal wall cells.
    if (tx <= ty) {
      ix += ax.step;
      t_enter = tx;
    } else {
      iy += ay.step;
      t_enter = ty;
    }
  }
}

template <typename Visitor>
RayHit CastRayMarching(const OccupancyGrid& g, const DistanceField& df, double ox, double oy, double angle,
                       double max_range, Visitor& visitor) {
  using namespace ray_cast_detail;
  const double r = g.resolution_m();
  const Axis ax = MakeAxis(ox, std::cos(angle));
  const Axis ay = MakeAxis(oy, std::sin(angle));
  // A jump must clear every stopping cell from any point of the current
  // cell (sqrt(2)*r) and keep half a cell of margin so that rounding can
  // never land it on or across a wall.
  const double kJumpMargin = (std::sqrt(2.0) + 0.5) * r;
  int ix = static_cast<int>(std::floor(ox / r));
  int iy = static_cast<int>(std::floor(oy / r));
  RayHit hit;
  double t_enter = 0.0;  // time at which the ray entered cell (ix, iy)
  while (true) {
    if (t_enter >= max_range) {
      hit.range_m = static_cast<float>(max_range);
      return hit;
    }
    if (!g.Contains(ix, iy)) {
      hit.range_m = static_cast<float>(t_enter);
      return hit;
    }
    visitor.Fetch(FetchKind::kDistanceCell, static_cast<std::uint32_t>(g.Index(ix, iy)));
    ++hit.nodes;
    const double d = df.At(ix, iy);
    if (d == 0.0) {  // the cell itself stops the ray
      hit.range_m = static_cast<float>(t_enter);
      return hit;
    }
    const double tx = ax.BoundaryTime(ix, r), ty = ay.BoundaryTime(iy, r);
    const double t_exit = std::min(tx, ty);
    const double jump = d - kJumpMargin;
    if (jump > r) {
      // Jump from the current cell's entry point. Accept the landing cell
      // only if the ray crosses its interior; otherwise (rounding at a
      // boundary) take the exact single step below instead.
      const double t_land = t_enter + jump;
      const int jx = static_cast<int>(std::floor((ox + t_land * ax.dir) / r));
      const int jy = static_cast<int>(std::floor((oy + t_land * ay.dir) / r));
      const double t_in = std::max(ax.EntryTime(jx, r), ay.EntryTime(jy, r));
      const double t_out = std::min(ax.BoundaryTime(jx, r), ay.BoundaryTime(jy, r));
      if (t_in < t_out && t_in > t_enter) {
        ix = jx;
        iy = jy;
        t_enter = t_in;
        continue;
      }
    }
    if (tx <= ty) {  // same tie rule as CastDda
      ix += ax.step;
    } else {
      iy += ay.step;
    }
    t_enter = t_exit;
  }
}

// Dispatches on the scene's method.
template <typename Visitor>
RayHit CastRay(const RayCastScene& scene, double ox, double oy, double angle, double max_range, Visitor& visitor) {
  switch (scene.method()) {
    case RayCastMethod::kMarch: return CastMarch(scene.grid(), ox, oy, angle, max_range, visitor);
    case RayCastMethod::kDda: return CastDda(scene.grid(), ox, oy, angle, max_range, visitor);
    case RayCastMethod::kRayMarching:
      return CastRayMarching(scene.grid(), *scene.distance_field(), ox, oy, angle, max_range, visitor);
  }
  return {};
}

inline RayHit CastRay(const RayCastScene& scene, double ox, double oy, double angle, double max_range) {
  NoFetchVisitor none;
  return CastRay(scene, ox, oy, angle, max_range, none);
}

}  // namespace rc
