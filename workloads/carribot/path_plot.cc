#include "workloads/carribot/path_plot.h"

#include <algorithm>
#include <stdexcept>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "common/atomic_file.h"
#include "maps/image_codec.h"
#include "workloads/carribot/footprint_geometry.h"

namespace rc {
namespace {

const cv::Scalar kPathColour(0, 0, 255);  // BGR
const cv::Scalar kStartColour(0, 160, 0);
const cv::Scalar kGoalColour(200, 0, 200);
const cv::Scalar kFootprintColour(220, 90, 0);
constexpr int kSubpixelBits = 4;  // cv drawing takes fixed-point coordinates

class Canvas {
 public:
  Canvas(const OccupancyGrid& grid, int magnification)
      : size_y_(grid.size_y()),
        k_(magnification),
        image_(grid.size_y() * magnification, grid.size_x() * magnification, CV_8UC3) {
    for (int ix = 0; ix < grid.size_x(); ++ix) {
      for (int iy = 0; iy < grid.size_y(); ++iy) {
        const CellState s = grid.At(ix, iy);
        const unsigned char v = s == CellState::kFree ? 255 : s == CellState::kOccupied ? 0 : 160;
        const int row = (size_y_ - 1 - iy) * k_, col = ix * k_;
        image_(cv::Rect(col, row, k_, k_)).setTo(cv::Scalar(v, v, v));
      }
    }
  }

  // A point in grid units (cells, y up) as a fixed-point pixel.
  cv::Point Pixel(double x_cells, double y_cells) const {
    const double scale = k_ * static_cast<double>(1 << kSubpixelBits);
    return {static_cast<int>(x_cells * scale + 0.5), static_cast<int>((size_y_ - y_cells) * scale + 0.5)};
  }
  int thickness(int base) const { return std::max(1, base * k_ / 4); }
  cv::Mat3b& image() { return image_; }

 private:
  int size_y_;
  int k_;
  cv::Mat3b image_;
};

void DrawFootprint(Canvas& canvas, const PathState& s, const RectangleFootprint& f, int heading_count,
                   double resolution_m) {
  const Vec2 u = HeadingAxis(s.heading, heading_count);
  const Vec2 v{-u.y, u.x};
  const double hl = 0.5 * f.length_m / resolution_m, hw = 0.5 * f.width_m / resolution_m;
  const double cx = s.x + 0.5, cy = s.y + 0.5;
  std::vector<cv::Point> corners;
  for (const auto& [a, b] : {std::pair{1, 1}, {1, -1}, {-1, -1}, {-1, 1}})
    corners.push_back(canvas.Pixel(cx + a * hl * u.x + b * hw * v.x, cy + a * hl * u.y + b * hw * v.y));
  cv::polylines(canvas.image(), corners, true, kFootprintColour, canvas.thickness(1), cv::LINE_AA, kSubpixelBits);
}

}  // namespace

void WritePathPlot(const std::string& png_path, const OccupancyGrid& grid, const PlanResult& result,
                   const PathPlotOptions& options) {
  const int longer = std::max(grid.size_x(), grid.size_y());
  const int magnification = std::clamp((512 + longer - 1) / longer, 1, 8);
  Canvas canvas(grid, magnification);
  const std::vector<PathState>& path = result.path;
  for (std::size_t i = 1; i < path.size(); ++i)
    cv::line(canvas.image(), canvas.Pixel(path[i - 1].x + 0.5, path[i - 1].y + 0.5),
             canvas.Pixel(path[i].x + 0.5, path[i].y + 0.5), kPathColour, canvas.thickness(2), cv::LINE_AA,
             kSubpixelBits);
  if (!path.empty()) {
    if (options.footprint && path.front().heading != kAnyHeading) {
      const int heading_count = options.footprint->heading_count;
      const std::size_t outlines = static_cast<std::size_t>(std::max(options.footprint_outlines, 0)) + 2;
      const std::size_t stride = std::max<std::size_t>(1, (path.size() + outlines - 1) / outlines);
      for (std::size_t i = 0; i < path.size(); i += stride)
        DrawFootprint(canvas, path[i], *options.footprint, heading_count, grid.resolution_m());
      DrawFootprint(canvas, path.back(), *options.footprint, heading_count, grid.resolution_m());
    }
    const int radius = std::max(3, 2 * magnification) << kSubpixelBits;
    cv::circle(canvas.image(), canvas.Pixel(path.front().x + 0.5, path.front().y + 0.5), radius, kStartColour,
               cv::FILLED, cv::LINE_AA, kSubpixelBits);
    cv::circle(canvas.image(), canvas.Pixel(path.back().x + 0.5, path.back().y + 0.5), radius, kGoalColour, cv::FILLED,
               cv::LINE_AA, kSubpixelBits);
  }
  std::vector<unsigned char> png;
  if (!EncodePng(canvas.image(), png)) throw std::runtime_error(png_path + ": PNG encoding failed");
  AtomicFile file(png_path);
  file.stream().write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
  file.Commit();
}

}  // namespace rc
