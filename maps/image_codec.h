#pragma once
// Image files through OpenCV's imgcodecs, opened on demand
// (common/on_demand_module.h): imgcodecs brings about 120 shared libraries
// (GDAL, DICOM, ...) that a run with no image map and no plot never needs,
// so they live in librcbench_imgcodecs.so (image_codec_module.cc) and load
// on the first call here.
#include <cstddef>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace rc {

// cv::imread(path, cv::IMREAD_UNCHANGED): an empty Mat when the file cannot
// be decoded; a decoder may throw cv::Exception on a corrupt file.
cv::Mat DecodeImageFile(const std::string& path);

// cv::imencode(".png", image, png): false when encoding fails.
bool EncodePng(const cv::Mat& image, std::vector<unsigned char>& png);

// The module's table (one build makes the module and its callers, so the
// table passes C++ types; `size` guards against a stale module).
struct ImageCodecModuleApi {
  std::size_t size = sizeof(ImageCodecModuleApi);
  cv::Mat (*decode_image_file)(const std::string& path);
  bool (*encode_png)(const cv::Mat& image, std::vector<unsigned char>& png);
};

}  // namespace rc

// The module's one exported symbol.
extern "C" const rc::ImageCodecModuleApi* rc_image_codec_module_api();
