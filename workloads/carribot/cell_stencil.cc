#include "workloads/carribot/cell_stencil.h"

#include <algorithm>

namespace rc {

CellStencil::CellStencil(std::vector<CellOffset> offsets) {
  std::sort(offsets.begin(), offsets.end());
  offsets.erase(std::unique(offsets.begin(), offsets.end()), offsets.end());
  cell_count_ = offsets.size();
  for (const CellOffset& o : offsets) {
    if (!runs_.empty() && runs_.back().dx == o.dx && runs_.back().dy_hi + 1 == o.dy)
      runs_.back().dy_hi = o.dy;
    else
      runs_.push_back({o.dx, o.dy, o.dy});
  }
}

bool CellStencil::Contains(CellOffset o) const {
  for (const CellRun& r : runs_)
    if (r.dx == o.dx && r.dy_lo <= o.dy && o.dy <= r.dy_hi) return true;
  return false;
}

std::vector<CellOffset> CellStencil::Offsets() const {
  std::vector<CellOffset> out;
  out.reserve(cell_count_);
  for (const CellRun& r : runs_)
    for (int dy = r.dy_lo; dy <= r.dy_hi; ++dy) out.push_back({r.dx, dy});
  return out;
}

CellStencil CellStencil::Shifted(int dx, int dy) const {
  std::vector<CellOffset> out = Offsets();
  for (CellOffset& o : out) o = {o.dx + dx, o.dy + dy};
  return CellStencil(std::move(out));
}

CellStencil CellStencil::Minus(const CellStencil& other) const {
  std::vector<CellOffset> out;
  for (const CellOffset& o : Offsets())
    if (!other.Contains(o)) out.push_back(o);
  return CellStencil(std::move(out));
}

CellStencil CellStencil::Union(const CellStencil& other) const {
  std::vector<CellOffset> out = Offsets();
  const std::vector<CellOffset> more = other.Offsets();
  out.insert(out.end(), more.begin(), more.end());
  return CellStencil(std::move(out));
}

ColumnBlockIndex::ColumnBlockIndex(const OccupancyGrid& grid)
    : size_x_(grid.size_x()), size_y_(grid.size_y()), next_blocked_(grid.cell_count()) {
  for (int ix = 0; ix < size_x_; ++ix) {
    std::int32_t next = size_y_;
    for (int iy = size_y_ - 1; iy >= 0; --iy) {
      if (!grid.IsFree(ix, iy)) next = iy;
      next_blocked_[grid.Index(ix, iy)] = next;
    }
  }
}

}  // namespace rc
