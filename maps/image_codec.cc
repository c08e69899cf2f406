#include "maps/image_codec.h"

#include "common/on_demand_module.h"

namespace rc {
namespace {

const ImageCodecModuleApi& Module() {
  static const ImageCodecModuleApi& api =
      OpenModuleApi<ImageCodecModuleApi>("imgcodecs", "rc_image_codec_module_api");
  return api;
}

}  // namespace

cv::Mat DecodeImageFile(const std::string& path) { return Module().decode_image_file(path); }

bool EncodePng(const cv::Mat& image, std::vector<unsigned char>& png) { return Module().encode_png(image, png); }

}  // namespace rc
