#include "workloads/carribot/footprint_stencils.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "workloads/carribot/octile_steps.h"

namespace rc {
namespace {

// Every offset within `reach` cells of the centre cell for which `touches`
// holds. The reach is generous; the exact test decides.
template <class Touches>
CellStencil Rasterize(double reach, const Touches& touches) {
  const int r = static_cast<int>(std::ceil(reach)) + 1;
  std::vector<CellOffset> cells;
  for (int dx = -r; dx <= r; ++dx)
    for (int dy = -r; dy <= r; ++dy)
      if (touches(OffsetCellSquare(dx, dy))) cells.push_back({dx, dy});
  return CellStencil(std::move(cells));
}

}  // namespace

FootprintStencils::FootprintStencils(double length_cells, double width_cells, int heading_count)
    : half_length_(0.5 * length_cells), half_width_(0.5 * width_cells), heading_count_(heading_count) {
  if (!(length_cells >= 0) || !(width_cells >= 0) || !std::isfinite(length_cells) || !std::isfinite(width_cells))
    throw std::invalid_argument("footprint length and width must be finite and >= 0 cells");
  if (heading_count < kMinHeadings || heading_count > kMaxHeadings)
    throw std::invalid_argument("heading count " + std::to_string(heading_count) + " is outside [" +
                                std::to_string(kMinHeadings) + ", " + std::to_string(kMaxHeadings) + "]");
  per_heading_.resize(heading_count);
  for (int h = 0; h < heading_count; ++h)
    per_heading_[h].footprint =
        Rasterize(half_diagonal_cells(), [&](const CellSquare& s) { return BoxTouchesSquare(Box(h), s); });
  for (int h = 0; h < heading_count; ++h) {
    HeadingStencils& hs = per_heading_[h];
    for (int d = 0; d < 8; ++d) {
      const GridStep step = kOctileSteps[d];
      hs.translation_extra[d] =
          TranslationSweep(h, d).Minus(hs.footprint.Union(hs.footprint.Shifted(step.dx, step.dy)));
    }
    const int next = (h + 1) % heading_count;
    hs.rotation_extra = RotationSweep(h).Minus(hs.footprint.Union(per_heading_[next].footprint));
  }
}

double FootprintStencils::half_diagonal_cells() const { return std::hypot(half_length_, half_width_); }

CenteredBox FootprintStencils::Box(int heading) const {
  return {half_length_, half_width_, HeadingAxis(heading, heading_count_)};
}

CellStencil FootprintStencils::TranslationSweep(int heading, int step) const {
  const Vec2 d{static_cast<double>(kOctileSteps[step].dx), static_cast<double>(kOctileSteps[step].dy)};
  return Rasterize(half_diagonal_cells() + 2.0,
                   [&](const CellSquare& s) { return SweptBoxTouchesSquare(Box(heading), d, s); });
}

CellStencil FootprintStencils::RotationSweep(int heading) const {
  const Vec2 end_axis = HeadingAxis(heading + 1, heading_count_);
  return Rasterize(half_diagonal_cells(),
                   [&](const CellSquare& s) { return RotationSweepTouchesSquare(Box(heading), end_axis, s); });
}

}  // namespace rc
