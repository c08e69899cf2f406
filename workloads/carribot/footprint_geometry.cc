#include "workloads/carribot/footprint_geometry.h"

#include <algorithm>
#include <array>

namespace rc {
namespace {

// True when the closed intervals [a_lo, a_hi] and [b_lo, b_hi] are disjoint.
bool Disjoint(double a_lo, double a_hi, double b_lo, double b_hi) { return a_hi < b_lo || b_hi < a_lo; }

// Projection interval of the square on axis n (n need not be unit length).
void ProjectSquare(const CellSquare& s, Vec2 n, double* lo, double* hi) {
  const double cx = 0.5 * (s.lo.x + s.hi.x), cy = 0.5 * (s.lo.y + s.hi.y);
  const double ex = 0.5 * (s.hi.x - s.lo.x), ey = 0.5 * (s.hi.y - s.lo.y);
  const double centre = n.x * cx + n.y * cy;
  const double radius = std::abs(n.x) * ex + std::abs(n.y) * ey;
  *lo = centre - radius;
  *hi = centre + radius;
}

// Projection interval of box + [0, d] on axis n.
void ProjectSweptBox(const CenteredBox& b, Vec2 d, Vec2 n, double* lo, double* hi) {
  const Vec2 across{-b.axis.y, b.axis.x};
  const double radius = b.half_length * std::abs(Dot(b.axis, n)) + b.half_width * std::abs(Dot(across, n));
  const double shift = Dot(d, n);
  *lo = -radius + std::min(0.0, shift);
  *hi = radius + std::max(0.0, shift);
}

bool SeparatedOn(const CenteredBox& b, Vec2 d, const CellSquare& s, Vec2 n) {
  double box_lo, box_hi, square_lo, square_hi;
  ProjectSweptBox(b, d, n, &box_lo, &box_hi);
  ProjectSquare(s, n, &square_lo, &square_hi);
  return Disjoint(box_lo, box_hi, square_lo, square_hi);
}

// Convex polygon with at most 4 + 2 vertices (a square clipped by two
// half-planes), counter-clockwise.
struct SmallPolygon {
  std::array<Vec2, 8> v;
  int size = 0;
};

// Keeps the closed half-plane Cross(edge, p) >= 0 (left of the direction
// `edge` through the origin). Sutherland-Hodgman on one plane.
SmallPolygon ClipLeftOf(const SmallPolygon& in, Vec2 edge) {
  SmallPolygon out;
  for (int i = 0; i < in.size; ++i) {
    const Vec2 a = in.v[i], b = in.v[(i + 1) % in.size];
    const double sa = Cross(edge, a), sb = Cross(edge, b);
    if (sa >= 0) out.v[out.size++] = a;
    if ((sa >= 0) != (sb >= 0)) {
      const double t = sa / (sa - sb);
      out.v[out.size++] = {a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)};
    }
  }
  return out;
}

double SquaredDistanceToSegment(Vec2 a, Vec2 b) {
  const Vec2 ab{b.x - a.x, b.y - a.y};
  const double len2 = Dot(ab, ab);
  double t = len2 > 0 ? -Dot(a, ab) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  const Vec2 p{a.x + t * ab.x, a.y + t * ab.y};
  return Dot(p, p);
}

Vec2 Rotate(Vec2 p, Vec2 by_axis) { return {p.x * by_axis.x - p.y * by_axis.y, p.x * by_axis.y + p.y * by_axis.x}; }

}  // namespace

Vec2 HeadingAxis(int heading, int heading_count) {
  constexpr double kTwoPi = 2.0 * 3.14159265358979323846;
  const int n = heading_count;
  const int k = ((heading % n) + n) % n;
  if (n % 4 != 0) {
    if ((4 * k) % n == 0) return HeadingAxis(4 * k / n, 4);
    return {std::cos(kTwoPi * k / n), std::sin(kTwoPi * k / n)};
  }
  // Within a quadrant, mirror the upper half onto the lower one so that
  // angles a and 90 - a get swapped components, 45 degrees gets two equal
  // ones; then turn by whole quadrants, which is exact.
  const int quarter = n / 4, quadrant = k / quarter, m = k % quarter;
  Vec2 u;
  if (2 * m == quarter)
    u = {std::sqrt(0.5), std::sqrt(0.5)};
  else if (2 * m < quarter)
    u = {std::cos(kTwoPi * m / n), std::sin(kTwoPi * m / n)};
  else
    u = {std::sin(kTwoPi * (quarter - m) / n), std::cos(kTwoPi * (quarter - m) / n)};
  for (int q = 0; q < quadrant; ++q) u = {0.0 - u.y, u.x};  // 0.0 - 0.0 is +0.0, never -0.0
  return u;
}

Vec2 BoundingHalfExtents(const CenteredBox& b) {
  const Vec2 u = b.axis;
  return {b.half_length * std::abs(u.x) + b.half_width * std::abs(u.y),
          b.half_length * std::abs(u.y) + b.half_width * std::abs(u.x)};
}

bool SweptBoxTouchesSquare(const CenteredBox& box, Vec2 d, const CellSquare& square) {
  if (SeparatedOn(box, d, square, {1.0, 0.0})) return false;
  if (SeparatedOn(box, d, square, {0.0, 1.0})) return false;
  if (SeparatedOn(box, d, square, box.axis)) return false;
  if (SeparatedOn(box, d, square, {-box.axis.y, box.axis.x})) return false;
  if ((d.x != 0.0 || d.y != 0.0) && SeparatedOn(box, d, square, {-d.y, d.x})) return false;
  return true;
}

bool SectorTouchesSquare(const Sector& sector, const CellSquare& square) {
  if (square.lo.x <= 0 && 0 <= square.hi.x && square.lo.y <= 0 && 0 <= square.hi.y) return true;  // apex
  SmallPolygon poly;
  poly.v[0] = {square.lo.x, square.lo.y};
  poly.v[1] = {square.hi.x, square.lo.y};
  poly.v[2] = {square.hi.x, square.hi.y};
  poly.v[3] = {square.lo.x, square.hi.y};
  poly.size = 4;
  poly = ClipLeftOf(poly, sector.from);                   // counter-clockwise of `from`
  poly = ClipLeftOf(poly, {-sector.to.x, -sector.to.y});  // clockwise of `to`
  if (poly.size == 0) return false;
  // The apex lies outside the square, hence outside the clipped polygon: the
  // nearest point is on its boundary.
  double nearest = SquaredDistanceToSegment(poly.v[0], poly.v[0]);
  for (int i = 0; i < poly.size; ++i)
    nearest = std::min(nearest, SquaredDistanceToSegment(poly.v[i], poly.v[(i + 1) % poly.size]));
  return nearest <= sector.radius * sector.radius;
}

bool RotationSweepTouchesSquare(const CenteredBox& box, Vec2 end_axis, const CellSquare& square) {
  if (BoxTouchesSquare(box, square)) return true;
  CenteredBox end = box;
  end.axis = end_axis;
  if (BoxTouchesSquare(end, square)) return true;
  // The turn as a rotation that maps box.axis onto end_axis.
  const Vec2 turn{Dot(box.axis, end_axis), Cross(box.axis, end_axis)};
  const Vec2 across{-box.axis.y, box.axis.x};
  const double radius = std::sqrt(box.half_length * box.half_length + box.half_width * box.half_width);
  for (const double sl : {-1.0, 1.0}) {
    for (const double sw : {-1.0, 1.0}) {
      const Vec2 corner{sl * box.half_length * box.axis.x + sw * box.half_width * across.x,
                        sl * box.half_length * box.axis.y + sw * box.half_width * across.y};
      if (SectorTouchesSquare({radius, corner, Rotate(corner, turn)}, square)) return true;
    }
  }
  return false;
}

}  // namespace rc
