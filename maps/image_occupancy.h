#pragma once
// Turning image pixels into cell states with ROS map_server's rules, shared
// by the ROS YAML loader and the plain image loader.
//
// Pixel value (as ROS 1 map_server, navigation/map_server image_loader.cpp):
//   v = mean of the pixel's channels. In trinary mode an alpha channel is
//   averaged in with the colours (map_server keeps this for compatibility);
//   in scale and raw mode alpha is left out.
//   p = (255 - v) / 255, or with negate p = v / 255 (computed as map_server
//   does: v := 255 - v first).
// Trinary mode (the default): occupied if p > occupied_thresh, free if
//   p < free_thresh, unknown otherwise. The comparisons are strict, as in
//   map_server's code (its header comment says >= and <=; the code wins):
//   a pixel exactly at a threshold is unknown.
// Scale mode: map_server gives 100 (p > occupied_thresh), 0 (p < free_thresh)
//   or, in between, a partial occupancy 0..99 (-1 if fully transparent).
//   A three-state grid has no partial occupancy; like AMCL, which only
//   believes 0 and 100, we make the in-between cells unknown. So scale mode
//   reduces to the trinary rule on the alpha-free channel mean.
// Raw mode: the pixel is the occupancy in percent. 0..100 is classified with
//   the same thresholds applied to v / 100 (so 0 is free and 100 occupied at
//   the defaults); 255 (-1 as a signed byte) is unknown; any other value, or
//   a colour pixel whose channels disagree to give a fractional mean, is not
//   a valid occupancy and raises an InputError naming the pixel. negate has
//   no agreed meaning in raw mode (ROS 1 applies it, Nav2 ignores it), so the
//   callers reject it.
//
// Orientation: image row 0 is the top of the map (largest y). Cell ix is the
// image column and iy = height - 1 - row, so cell (0, 0) is the bottom-left
// pixel, whose outer corner is the ROS map origin.
//
// Accepted images: anything OpenCV decodes to 8 bits per channel with 1, 3
// or 4 channels (grey, BGR, BGRA; grey+alpha PNGs decode as BGRA); a PNM
// only once image_pnm_check.h has found it well formed, a PNG once
// image_png_check.h has found its chunks sound. 16-bit
// images are rejected rather than rescaled. Palette PNGs decode to their
// colours; map_server (SDL) would read the palette index instead.
#include <string>

#include "maps/cell_classes.h"
#include "maps/occupancy_grid.h"

namespace rc {

enum class ImageMapMode { kTrinary, kScale, kRaw };

std::string ToString(ImageMapMode mode);  // "trinary", "scale", "raw"

struct PixelThresholds {
  double occupied_thresh = 0.65;  // p above this: occupied (map_server default)
  double free_thresh = 0.196;     // p below this: free (map_server default)
  bool negate = false;            // true: dark pixels are free
};

// True when 0 <= free_thresh < occupied_thresh <= 1 and both are finite.
// Otherwise fills *field with the offending key ("free_thresh" or
// "occupied_thresh") and *problem with the reason.
bool CheckPixelThresholds(const PixelThresholds& t, std::string* field, std::string* problem);

// Classifies one pixel's channel mean v (0..255) in trinary or scale mode.
CellState ClassifyPixelMean(double v, const PixelThresholds& t);

// The field that names one pixel in an InputError: "pixel (row R, column C)",
// 0-based, image row 0 at the top (as image viewers count).
std::string PixelField(int row, int column);

// Reads the image at image_path and classifies every pixel (see above).
// Throws InputError(image_path, 0, ...) when the image cannot be opened or
// is a directory, is not one of the map image formats (image_signature.h),
// cannot be decoded, or has an unsupported depth or channel count; a PNM's
// malformed header or raster is located by line and field
// (image_pnm_check.h); raw mode names the offending pixel's row and column.
// Thresholds must be valid.
// Adds each cell's class to *counts when given (raw 255 is never observed;
// every other unknown pixel lies between the thresholds).
OccupancyGrid ReadImageGrid(const std::string& image_path, double resolution_m, const PixelThresholds& thresholds,
                            ImageMapMode mode, CellClassCounts* counts = nullptr);

}  // namespace rc
