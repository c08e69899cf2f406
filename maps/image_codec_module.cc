// The body of librcbench_imgcodecs.so: OpenCV's image codecs behind one
// table (image_codec.h).
#include <opencv2/imgcodecs.hpp>

#include "maps/image_codec.h"

extern "C" __attribute__((visibility("default"))) const rc::ImageCodecModuleApi* rc_image_codec_module_api() {
  static const rc::ImageCodecModuleApi api = [] {
    rc::ImageCodecModuleApi a;
    a.decode_image_file = [](const std::string& path) { return cv::imread(path, cv::IMREAD_UNCHANGED); };
    a.encode_png = [](const cv::Mat& image, std::vector<unsigned char>& png) {
      return cv::imencode(".png", image, png);
    };
    return a;
  }();
  return &api;
}
