#include "maps/image_occupancy.h"

#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>

#include "common/input_error.h"
#include "common/text_fields.h"
#include "maps/grid_size_limits.h"
#include "maps/image_codec.h"
#include "maps/image_jpeg_check.h"
#include "maps/image_png_check.h"
#include "maps/image_pnm_check.h"
#include "maps/image_signature.h"

namespace rc {
namespace {

constexpr int kRawUnknown = 255;  // -1 as the signed byte map_server stores

std::string Text(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

// Raw mode: the mean must be an exact occupancy percentage or 255.
CellClass ClassifyRawPixel(double v, const PixelThresholds& t, const std::string& image_path, int row, int column) {
  if (v == kRawUnknown) return CellClass::kUnobserved;
  if (v != std::floor(v) || v > 100.0)
    throw InputError(image_path, 0, PixelField(row, column),
                     "raw-mode value " + Text(v) + " is not an occupancy percentage (0..100) or 255 (unknown)");
  const double p = v / 100.0;
  if (p > t.occupied_thresh) return CellClass::kOccupied;
  if (p < t.free_thresh) return CellClass::kFree;
  return CellClass::kBetweenThresholds;
}

CellClass ClassifyPixelMeanClass(double v, const PixelThresholds& t) {
  // Same order of operations as map_server, so results match bit for bit.
  if (t.negate) v = 255.0 - v;
  const double p = (255.0 - v) / 255.0;
  if (p > t.occupied_thresh) return CellClass::kOccupied;
  if (p < t.free_thresh) return CellClass::kFree;
  return CellClass::kBetweenThresholds;
}

}  // namespace

std::string PixelField(int row, int column) {
  return "pixel (row " + std::to_string(row) + ", column " + std::to_string(column) + ")";
}

std::string ToString(ImageMapMode mode) {
  switch (mode) {
    case ImageMapMode::kTrinary: return "trinary";
    case ImageMapMode::kScale: return "scale";
    case ImageMapMode::kRaw: return "raw";
  }
  return "?";
}

bool CheckPixelThresholds(const PixelThresholds& t, std::string* field, std::string* problem) {
  auto fail = [&](const char* f, const std::string& p) {
    *field = f;
    *problem = p;
    return false;
  };
  if (!std::isfinite(t.occupied_thresh) || t.occupied_thresh < 0.0 || t.occupied_thresh > 1.0)
    return fail("occupied_thresh", "must be a number in [0, 1], got " + Text(t.occupied_thresh));
  if (!std::isfinite(t.free_thresh) || t.free_thresh < 0.0 || t.free_thresh > 1.0)
    return fail("free_thresh", "must be a number in [0, 1], got " + Text(t.free_thresh));
  if (t.free_thresh >= t.occupied_thresh)
    return fail("free_thresh",
                "must be below occupied_thresh (" + Text(t.free_thresh) + " >= " + Text(t.occupied_thresh) + ")");
  return true;
}

CellState ClassifyPixelMean(double v, const PixelThresholds& t) { return StateOf(ClassifyPixelMeanClass(v, t)); }

OccupancyGrid ReadImageGrid(const std::string& image_path, double resolution_m, const PixelThresholds& thresholds,
                            ImageMapMode mode, CellClassCounts* counts) {
  // Checked first: OpenCV would also print its own warning for a missing file.
  RejectDirectory(image_path);
  std::ifstream file(image_path, std::ios::binary);
  if (!file) throw InputError(image_path, 0, "", "cannot open image file");
  std::string head(8, '\0');
  file.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(file.gcount()));
  const std::optional<std::string> format = MapImageFormatOf(head);
  if (!format)
    throw InputError(image_path, 0, "",
                     std::string("not a ") + kMapImageFormats + " image (its first bytes match none of them)");
  // OpenCV misreads some malformed PNMs and reports none of them well
  // (image_pnm_check.h), so a PNM decodes only once it has passed this.
  if (*format == "PNM") CheckPnmImage(image_path);
  // libpng prints its own line on stderr for a truncated or corrupt PNG
  // (image_png_check.h), so a PNG decodes only once its chunks are sound.
  if (*format == "PNG") CheckPngImage(image_path);
  // libjpeg prints "Premature end of JPEG file" or "Corrupt JPEG data: ..."
  // and fills the rest grey (image_jpeg_check.h), so a JPEG decodes here
  // only once libjpeg has decoded it quietly without an error or warning.
  if (*format == "JPEG") CheckJpegImage(image_path);
  // A corrupt file can make a decoder throw (cv::Exception) instead of
  // returning an empty image.
  cv::Mat image;
  try {
    image = DecodeImageFile(image_path);
  } catch (const cv::Exception& e) {
    throw InputError(image_path, 0, "", std::string("cannot decode the image (corrupt): ") + e.what());
  }
  if (image.empty())
    throw InputError(image_path, 0, "", "cannot decode the image (not an image format OpenCV knows, or corrupt)");
  if (image.depth() != CV_8U)
    throw InputError(image_path, 0, "",
                     "only 8-bit images are supported (this one has " + std::to_string(8 * image.elemSize1()) +
                         "-bit channels)");
  const int channels = image.channels();
  if (channels != 1 && channels != 3 && channels != 4)
    throw InputError(image_path, 0, "",
                     "unsupported channel count " + std::to_string(channels) + " (expected 1, 3 or 4)");
  CheckMapSize(image_path, 0, "", image.cols, image.rows);

  // Alpha is the last channel of a 4-channel image (BGRA).
  const bool has_alpha = channels == 4;
  const int averaged = (has_alpha && mode != ImageMapMode::kTrinary) ? channels - 1 : channels;
  OccupancyGrid grid(image.cols, image.rows, resolution_m, CellState::kUnknown);
  for (int row = 0; row < image.rows; ++row) {
    const std::uint8_t* pixel = image.ptr<std::uint8_t>(row);
    const int iy = image.rows - 1 - row;
    for (int column = 0; column < image.cols; ++column, pixel += channels) {
      int sum = 0;
      for (int k = 0; k < averaged; ++k) sum += pixel[k];
      const double mean = sum / static_cast<double>(averaged);
      const CellClass c = mode == ImageMapMode::kRaw ? ClassifyRawPixel(mean, thresholds, image_path, row, column)
                                                     : ClassifyPixelMeanClass(mean, thresholds);
      if (counts) counts->Add(c);
      grid.Set(column, iy, StateOf(c));
    }
  }
  return grid;
}

}  // namespace rc
