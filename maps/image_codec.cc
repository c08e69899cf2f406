#include "maps/image_codec.h"

#include <stdexcept>

#include "common/on_demand_module.h"

namespace rc {
namespace {

const ImageCodecModuleApi& Module() {
  static const ImageCodecModuleApi* const api = [] {
    using Entry = const ImageCodecModuleApi* (*)();
    const auto entry = reinterpret_cast<Entry>(OpenModuleEntry("imgcodecs", "rc_image_codec_module_api"));
    const ImageCodecModuleApi* table = entry();
    if (table->size != sizeof(ImageCodecModuleApi))
      throw std::runtime_error("rcbench's imgcodecs module comes from another build (rebuild it with the binary)");
    return table;
  }();
  return *api;
}

}  // namespace

cv::Mat DecodeImageFile(const std::string& path) { return Module().decode_image_file(path); }

bool EncodePng(const cv::Mat& image, std::vector<unsigned char>& png) { return Module().encode_png(image, png); }

}  // namespace rc
