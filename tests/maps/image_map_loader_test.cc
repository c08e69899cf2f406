#include "maps/image_map_loader.h"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "map_test_util.h"
#include "support/input_error_expectations.h"
#include "support/temp_dir.h"

namespace rc {
namespace {

using test::ThrowsInputError;

std::string WritePng(const test::TempDir& dir, const std::string& name, const cv::Mat& image) {
  const std::string path = dir.Path(name);
  if (!cv::imwrite(path, image)) throw std::runtime_error("cannot write test image " + path);
  return path;
}

// 2 rows x 3 columns: top row black, white, mid-grey; bottom row white.
cv::Mat SmallImage() {
  cv::Mat image(2, 3, CV_8UC1, cv::Scalar(255));
  image.at<std::uint8_t>(0, 0) = 0;
  image.at<std::uint8_t>(0, 2) = 128;
  return image;
}

TEST(ImageMapLoader, UsesTheRosOrientationAndTrinaryRule) {
  test::TempDir dir;
  ImageMapOptions o;
  o.resolution_m = 0.1;
  const OccupancyGrid g = LoadImageMap(WritePng(dir, "m.png", SmallImage()), o);
  ASSERT_EQ(g.size_x(), 3);
  ASSERT_EQ(g.size_y(), 2);
  EXPECT_DOUBLE_EQ(g.resolution_m(), 0.1);
  EXPECT_EQ(test::Picture(g), "#.?\n...\n");
  EXPECT_EQ(g.At(0, 1), CellState::kOccupied);  // image row 0 is the top (iy = 1)
}

TEST(ImageMapLoader, ReadsPgmAndNegates) {
  test::TempDir dir;
  const std::string path = WritePng(dir, "m.pgm", SmallImage());
  ImageMapOptions o;
  o.resolution_m = 0.05;
  o.thresholds.negate = true;
  EXPECT_EQ(test::Picture(LoadImageMap(path, o)), ".#?\n###\n");
}

TEST(ImageMapLoader, ThresholdsComeFromTheOptionsAndAreStrict) {
  test::TempDir dir;
  cv::Mat image(1, 4, CV_8UC1);
  image.at<std::uint8_t>(0, 0) = 205;  // p = 0.196..
  image.at<std::uint8_t>(0, 1) = 204;  // p = 0.2 exactly
  image.at<std::uint8_t>(0, 2) = 51;   // p = 0.8 exactly
  image.at<std::uint8_t>(0, 3) = 50;   // p = 0.804..
  ImageMapOptions o;
  o.resolution_m = 1.0;
  o.thresholds.free_thresh = 0.2;
  o.thresholds.occupied_thresh = 0.8;
  EXPECT_EQ(test::Picture(LoadImageMap(WritePng(dir, "m.png", image), o)), ".??#\n");
}

TEST(ImageMapLoader, BadOptionsAreUsageErrors) {
  test::TempDir dir;
  const std::string path = WritePng(dir, "m.png", SmallImage());
  ImageMapOptions o;  // resolution left at 0: required
  EXPECT_THROW(LoadImageMap(path, o), UsageError);
  o.resolution_m = -0.1;
  EXPECT_THROW(LoadImageMap(path, o), UsageError);
  o.resolution_m = 0.1;
  o.thresholds.free_thresh = 0.9;
  EXPECT_THROW(LoadImageMap(path, o), UsageError);
}

TEST(ImageMapLoader, MissingOrUndecodableImageIsAnInputErrorNamingIt) {
  test::TempDir dir;
  ImageMapOptions o;
  o.resolution_m = 0.1;
  EXPECT_TRUE(ThrowsInputError([&] { LoadImageMap(dir.Path("absent.png"), o); }, 0, "", "cannot open image file"));
  const std::string junk = dir.Write("junk.png", "not a png");
  EXPECT_TRUE(ThrowsInputError([&] { LoadImageMap(junk, o); }, 0, "", "not a PNG, PNM (PGM/PPM/PBM), JPEG or BMP"));
  const std::string cut = dir.Write("cut.png", std::string("\x89PNG\r\n\x1a\n", 8) + "truncated");
  EXPECT_TRUE(ThrowsInputError([&] { LoadImageMap(cut, o); }, 0, "", "cannot decode"));
}

// A tests/fuzz finding: a DICOM file ("DICM" at byte 128) reached OpenCV's
// GDCM decoder, which aborts the process on a malformed file. Only the map
// image formats reach OpenCV now.
TEST(ImageMapLoader, OtherImageFormatsAreRefusedBeforeDecoding) {
  test::TempDir dir;
  ImageMapOptions o;
  o.resolution_m = 0.1;
  std::string dicom(128, '\xff');
  dicom += "DICM";
  const std::string path = dir.Write("scan.png", dicom);
  EXPECT_TRUE(ThrowsInputError([&] { LoadImageMap(path, o); }, 0, "", "its first bytes match none of them"));
  for (const char* pgm : {"P5\n2 1\n255\n\x01\x02", "P2 2 1 255 0 255\n"})
    EXPECT_NO_THROW(LoadImageMap(dir.Write("ok.pgm", pgm), o)) << pgm;
}

TEST(ImageMapLoader, SixteenBitImagesAreRejectedNotRescaled) {
  test::TempDir dir;
  const std::string path = WritePng(dir, "deep.png", cv::Mat(2, 2, CV_16UC1, cv::Scalar(1000)));
  ImageMapOptions o;
  o.resolution_m = 0.1;
  EXPECT_TRUE(ThrowsInputError([&] { LoadImageMap(path, o); }, 0, "", "only 8-bit"));
}

}  // namespace
}  // namespace rc
