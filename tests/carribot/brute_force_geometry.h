#pragma once
// Independent references for the footprint geometry: convex polygons clipped
// against a cell square (Sutherland-Hodgman). They share nothing with the
// separating-axis code under test.
#include <algorithm>
#include <cmath>
#include <vector>

#include "workloads/carribot/footprint_geometry.h"

namespace rc::test {

using Polygon = std::vector<Vec2>;

// Corners of the box centred at c, counter-clockwise.
inline Polygon BoxPolygon(Vec2 c, double half_length, double half_width, Vec2 axis) {
  const Vec2 across{-axis.y, axis.x};
  Polygon p;
  for (const auto& [a, b] : {std::pair{1, 1}, {-1, 1}, {-1, -1}, {1, -1}})
    p.push_back({c.x + a * half_length * axis.x + b * half_width * across.x,
                 c.y + a * half_length * axis.y + b * half_width * across.y});
  return p;
}

// Convex hull (Andrew's monotone chain); collinear points dropped.
inline Polygon ConvexHull(Polygon points) {
  std::sort(points.begin(), points.end(), [](Vec2 a, Vec2 b) { return a.x != b.x ? a.x < b.x : a.y < b.y; });
  if (points.size() < 3) return points;
  const auto turn = [](Vec2 o, Vec2 a, Vec2 b) { return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x); };
  Polygon hull(2 * points.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    while (k >= 2 && turn(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  for (std::size_t i = points.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && turn(hull[k - 2], hull[k - 1], points[i - 1]) <= 0) --k;
    hull[k++] = points[i - 1];
  }
  hull.resize(k - 1);
  return hull;
}

// Keeps the part of `poly` with coordinate `axis` (0 = x, 1 = y) on the
// closed side of `bound` (keep_below: <= bound, else >= bound).
inline Polygon ClipAxis(const Polygon& poly, int axis, double bound, bool keep_below) {
  Polygon out;
  const auto coord = [axis](Vec2 p) { return axis == 0 ? p.x : p.y; };
  const auto inside = [&](Vec2 p) { return keep_below ? coord(p) <= bound : coord(p) >= bound; };
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Vec2 a = poly[i], b = poly[(i + 1) % poly.size()];
    if (inside(a)) out.push_back(a);
    if (inside(a) != inside(b)) {
      const double t = (bound - coord(a)) / (coord(b) - coord(a));
      out.push_back({a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)});
    }
  }
  return out;
}

// True when the convex polygon and the closed square share a point.
inline bool PolygonTouchesSquare(Polygon poly, Vec2 lo, Vec2 hi) {
  poly = ClipAxis(poly, 0, lo.x, false);
  poly = ClipAxis(poly, 0, hi.x, true);
  poly = ClipAxis(poly, 1, lo.y, false);
  poly = ClipAxis(poly, 1, hi.y, true);
  return !poly.empty();
}

}  // namespace rc::test
