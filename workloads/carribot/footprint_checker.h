#pragma once
// The pluggable footprint collision check of CarriBot (OMPL's
// StateValidityChecker, narrowed to rectangles on a grid).
//
// A query is a rectangle placed on the map; the answer is whether it overlaps
// the interior or the boundary of any cell that is not free (touching counts),
// or reaches outside the map. RasterizedFootprintChecker is the exact CPU
// reference; the OBB-vs-quadtree collision kernel on the modelled GPU
// backends plugs in here, and must return the same answer for every cell and
// heading of a map (tests/carribot/footprint_checker_conformance.h checks it).
#include <cstddef>
#include <cstdint>

#include "workloads/carribot/footprint_geometry.h"

namespace rc {

// A footprint on the map, in grid units: 1 = one cell side, and the centre of
// cell (ix, iy) is (ix + 0.5, iy + 0.5). Working in cells rather than metres
// keeps lattice poses exact (see footprint_geometry.h).
struct FootprintPose {
  Vec2 center;
  CenteredBox box;
};

class FootprintChecker {
 public:
  virtual ~FootprintChecker() = default;
  virtual const char* name() const = 0;
  // collides[i] = 1 if poses[i] is in collision, else 0. One call is one
  // batch (e.g. the successors of one A* expansion).
  virtual void CheckPoses(const FootprintPose* poses, std::size_t count, std::uint8_t* collides) = 0;
  // Poses answered since construction.
  virtual std::uint64_t poses_checked() const = 0;
};

}  // namespace rc
