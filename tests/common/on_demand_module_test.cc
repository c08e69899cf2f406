// common/on_demand_module.h: modules open once, and a missing module or
// entry is an error that names what was tried.
#include "common/on_demand_module.h"

#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "maps/image_codec.h"

namespace rc {
namespace {

TEST(OnDemandModule, TheImageCodecsModuleOpensOnceAndGivesItsTable) {
  void* first = OpenModuleEntry("imgcodecs", "rc_image_codec_module_api");
  void* again = OpenModuleEntry("imgcodecs", "rc_image_codec_module_api");
  ASSERT_NE(first, nullptr);
  EXPECT_EQ(first, again);
  const auto api = reinterpret_cast<const ImageCodecModuleApi* (*)()>(first)();
  EXPECT_EQ(api->size, sizeof(ImageCodecModuleApi));
  // A round trip through the module: a 2 x 3 image, PNG-encoded and decoded.
  cv::Mat image(2, 3, CV_8UC1);
  for (int i = 0; i < 6; ++i) image.data[i] = static_cast<unsigned char>(40 * i);
  std::vector<unsigned char> png;
  ASSERT_TRUE(EncodePng(image, png));
  EXPECT_EQ(std::string(png.begin() + 1, png.begin() + 4), "PNG");
}

TEST(OnDemandModule, AMissingModuleNamesEveryPathTried) {
  try {
    OpenModuleEntry("no_such_module", "entry");
    FAIL() << "opened a module that does not exist";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("librcbench_no_such_module.so"), std::string::npos) << what;
    EXPECT_NE(what.find("no such file"), std::string::npos) << what;
  }
}

TEST(OnDemandModule, AMissingEntryIsNamed) {
  try {
    OpenModuleEntry("imgcodecs", "no_such_entry");
    FAIL() << "found an entry that does not exist";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("'no_such_entry'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rc
