#pragma once
// Exact overlap tests between a rectangular robot footprint (still, translated
// or rotated in place) and one grid cell, in grid units (1 = one cell side).
//
// Every region and every cell square is a closed set: touching counts as a
// collision, as the CarriBot issue asks. Callers pass coordinates relative to
// the footprint's centre. For the planner's lattice poses (centres on cell
// centres) the relative square of cell offset (dx, dy) is exactly
// [dx - 0.5, dx + 0.5] x [dy - 0.5, dy + 0.5], so a test made once for a
// stencil and one made for a pose anywhere on the map see the same numbers
// and return the same answer bit for bit.
//
// Methods:
//  - still and translated boxes: the 2D separating-axis theorem. A box swept
//    along a displacement d is the Minkowski sum box + [0, d], a convex
//    hexagon whose edge normals are the box axes and d's normal; with the
//    square's two axes these five axes decide overlap exactly. Projections are
//    computed analytically, so no vertex is ever rounded.
//  - rotation in place: the swept region of a rectangle turning about its
//    centre by less than 90 degrees is the union of the start box, the end
//    box and, for each corner, the circular sector (radius = half diagonal)
//    that the corner's direction sweeps. Why: the region is star-shaped about
//    the centre; in a direction that some corner passes through, it reaches
//    the full half diagonal, and in any other direction a single edge bounds
//    every intermediate box, whose distance is largest at the motion's ends.
//    A sector is tested by clipping the square to the sector's wedge and
//    comparing the clipped polygon's distance from the centre with the radius.
#include <cmath>

namespace rc {

struct Vec2 {
  double x = 0.0;
  double y = 0.0;
};

inline double Dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
inline double Cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }

// A rectangle centred on the origin: half_length along the unit `axis` (the
// heading), half_width across it. Zero extents are allowed (a segment or a
// point robot).
struct CenteredBox {
  double half_length = 0.0;
  double half_width = 0.0;
  Vec2 axis{1.0, 0.0};
};

// An axis-aligned closed square (or rectangle) [lo.x, hi.x] x [lo.y, hi.y].
struct CellSquare {
  Vec2 lo;
  Vec2 hi;
};

// The relative square of the cell at integer offset (dx, dy) from the cell
// that holds the footprint's centre at its centre.
inline CellSquare OffsetCellSquare(int dx, int dy) { return {{dx - 0.5, dy - 0.5}, {dx + 0.5, dy + 0.5}}; }

// Unit direction of heading index k of n: angle 2*pi*k/n from +x towards +y.
// Multiples of 90 degrees are exact (cos(pi/2) would otherwise be 6e-17 and
// turn exact contacts into rounding noise), and when 4 divides the heading
// count the axes are exactly symmetric: quarter turns map them onto each
// other and 45 degrees gives x == y.
Vec2 HeadingAxis(int heading, int heading_count);

// Half extents of the box's axis-aligned bounding box.
Vec2 BoundingHalfExtents(const CenteredBox& box);

// Closed-set overlap of the box swept from the origin along `displacement`
// (zero: the still box) with the square.
bool SweptBoxTouchesSquare(const CenteredBox& box, Vec2 displacement, const CellSquare& square);

inline bool BoxTouchesSquare(const CenteredBox& box, const CellSquare& square) {
  return SweptBoxTouchesSquare(box, Vec2{}, square);
}

// Closed circular sector with apex at the origin: the points within `radius`
// whose direction lies counter-clockwise from `from` to `to` (an angle below
// 180 degrees; the vectors need not be unit length).
struct Sector {
  double radius = 0.0;
  Vec2 from;
  Vec2 to;
};

bool SectorTouchesSquare(const Sector& sector, const CellSquare& square);

// Closed-set overlap of the region the box sweeps while turning
// counter-clockwise about its centre from box.axis to end_axis (less than 90
// degrees) with the square.
bool RotationSweepTouchesSquare(const CenteredBox& box, Vec2 end_axis, const CellSquare& square);

}  // namespace rc
