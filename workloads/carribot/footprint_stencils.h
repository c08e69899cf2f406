#pragma once
// The cells a rectangular footprint touches at each heading, and the extra
// cells each of its motions sweeps, as offsets from the cell holding its
// centre. Poses sit on cell centres, so these sets are the same at every
// cell of the map: rasterize once per heading, then checking a pose or a
// motion anywhere is a few column lookups (cell_stencil.h).
//
// Motions of a footprint state (x, y, heading):
//  - translation to one of the 8 neighbours, heading kept (octile_steps.h);
//  - rotation in place by one heading step, either way.
// A motion is collision-free when its whole swept region is: the start and
// end footprints plus the "extra" cells stored here (swept cells that neither
// end footprint touches). For a point footprint the extra cells of a diagonal
// step are its two corner cells, which is the octile no-corner-cutting rule.
//
// Precomputation: per heading, one exact test (footprint_geometry.h) per cell
// of the bounding square of each region: O(headings * 10 * (L + W + 3)^2).
#include <array>
#include <vector>

#include "workloads/carribot/cell_stencil.h"
#include "workloads/carribot/footprint_checker.h"

namespace rc {

class FootprintStencils {
 public:
  static constexpr int kMinHeadings = 4;
  static constexpr int kMaxHeadings = 64;

  // length along the heading and width across it, in cells (>= 0, finite).
  // Throws std::invalid_argument otherwise or for a heading count outside
  // [kMinHeadings, kMaxHeadings].
  FootprintStencils(double length_cells, double width_cells, int heading_count);

  int heading_count() const { return heading_count_; }
  double length_cells() const { return 2.0 * half_length_; }
  double width_cells() const { return 2.0 * half_width_; }
  // Distance from the centre to a corner (cells).
  double half_diagonal_cells() const;

  CenteredBox Box(int heading) const;
  FootprintPose PoseAt(int ix, int iy, int heading) const { return {{ix + 0.5, iy + 0.5}, Box(heading)}; }

  const CellStencil& footprint(int heading) const { return per_heading_[heading].footprint; }
  // Cells swept by step `step` (octile_steps.h) at `heading` but touched by
  // neither end footprint.
  const CellStencil& translation_extra(int heading, int step) const {
    return per_heading_[heading].translation_extra[step];
  }
  // Same for turning from `heading` to heading + 1 (counter-clockwise); the
  // clockwise turn from h + 1 to h sweeps the same region.
  const CellStencil& rotation_extra(int heading) const { return per_heading_[heading].rotation_extra; }

  // Full swept regions, for tests.
  CellStencil TranslationSweep(int heading, int step) const;
  CellStencil RotationSweep(int heading) const;

 private:
  struct HeadingStencils {
    CellStencil footprint;
    std::array<CellStencil, 8> translation_extra;
    CellStencil rotation_extra;
  };

  double half_length_ = 0.0;
  double half_width_ = 0.0;
  int heading_count_ = 0;
  std::vector<HeadingStencils> per_heading_;
};

}  // namespace rc
