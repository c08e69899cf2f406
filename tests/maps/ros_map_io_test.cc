#include "maps/ros_map_io.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <vector>

#include "map_test_util.h"
#include "support/input_error_expectations.h"
#include "support/temp_dir.h"

namespace rc {
namespace {

using test::ThrowsInputError;

// A binary PGM from rows of grey values, top row first.
std::string Pgm(const std::vector<std::vector<int>>& rows) {
  std::string out = "P5\n" + std::to_string(rows[0].size()) + " " + std::to_string(rows.size()) + "\n255\n";
  for (const auto& row : rows)
    for (int v : row) out += static_cast<char>(v);
  return out;
}

std::string Yaml(const std::string& image, const std::string& extra = "") {
  return "image: " + image +
         "\nresolution: 0.05\norigin: [-1.5, 2.25, 0.3]\nnegate: 0\n"
         "occupied_thresh: 0.65\nfree_thresh: 0.196\n" +
         extra;
}

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  return text.replace(text.find(from), from.size(), to);
}

TEST(RosMapIo, ImageRowZeroIsTheTopAndColumnsAreX) {
  test::TempDir dir;
  // 3 wide, 2 tall: top row black-white-grey, bottom row white-white-black.
  dir.Write("m.pgm", Pgm({{0, 254, 205}, {254, 254, 0}}));
  const RosMap map = LoadRosMap(dir.Write("m.yaml", Yaml("m.pgm")));
  ASSERT_EQ(map.grid.size_x(), 3);
  ASSERT_EQ(map.grid.size_y(), 2);
  EXPECT_EQ(test::Picture(map.grid), "#.?\n..#\n");
  EXPECT_EQ(map.grid.At(2, 0), CellState::kOccupied);  // bottom-right pixel
  EXPECT_EQ(map.grid.At(0, 1), CellState::kOccupied);  // top-left pixel
}

TEST(RosMapIo, ReturnsMetadataWithTheImageResolvedBesideTheYaml) {
  test::TempDir dir;
  dir.Write("maps/img/m.pgm", Pgm({{254}}));
  const std::string yaml = dir.Write("maps/m.yaml", Yaml("img/m.pgm", "mode: trinary\n"));
  const RosMap map = LoadRosMap(yaml);
  EXPECT_EQ(map.metadata.yaml_path, yaml);
  EXPECT_TRUE(std::filesystem::equivalent(map.metadata.image_path, dir.Path("maps/img/m.pgm")));
  EXPECT_DOUBLE_EQ(map.metadata.resolution_m, 0.05);
  EXPECT_DOUBLE_EQ(map.grid.resolution_m(), 0.05);
  EXPECT_DOUBLE_EQ(map.metadata.origin_x_m, -1.5);
  EXPECT_DOUBLE_EQ(map.metadata.origin_y_m, 2.25);
  EXPECT_DOUBLE_EQ(map.metadata.origin_yaw_rad, 0.3);
  EXPECT_EQ(map.metadata.mode, ImageMapMode::kTrinary);
  EXPECT_DOUBLE_EQ(map.metadata.thresholds.occupied_thresh, 0.65);
  EXPECT_DOUBLE_EQ(map.metadata.thresholds.free_thresh, 0.196);
  EXPECT_FALSE(map.metadata.thresholds.negate);
}

TEST(RosMapIo, AbsoluteImagePathIsUsedAsIs) {
  test::TempDir dir;
  const std::string image = dir.Write("elsewhere/m.pgm", Pgm({{0}}));
  const RosMap map = LoadRosMap(dir.Write("yaml/m.yaml", Yaml(image)));
  EXPECT_EQ(map.grid.At(0, 0), CellState::kOccupied);
}

// map_server compares strictly: a pixel exactly at a threshold is unknown.
// 51/255 is exactly 0.2 in double arithmetic, as is 204/255 == 0.8.
TEST(RosMapIo, PixelsExactlyAtAThresholdAreUnknown) {
  test::TempDir dir;
  // p = (255 - v) / 255: v=205 -> 0.196.. (free), v=204 -> 0.2 (edge),
  // v=51 -> 0.8 (edge), v=50 -> 0.804.. (occupied).
  dir.Write("m.pgm", Pgm({{205, 204, 51, 50}}));
  const std::string yaml = dir.Write("m.yaml",
                                     "image: m.pgm\nresolution: 1\norigin: [0, 0, 0]\nnegate: 0\n"
                                     "occupied_thresh: 0.8\nfree_thresh: 0.2\n");
  EXPECT_EQ(test::Picture(LoadRosMap(yaml).grid), ".??#\n");
}

TEST(RosMapIo, ThresholdsAtZeroAndOneMakePureColoursUnknown) {
  test::TempDir dir;
  dir.Write("m.pgm", Pgm({{255, 0, 128}}));
  const std::string yaml = dir.Write("m.yaml",
                                     "image: m.pgm\nresolution: 1\norigin: [0, 0, 0]\nnegate: 0\n"
                                     "occupied_thresh: 1.0\nfree_thresh: 0.0\n");
  EXPECT_EQ(test::Picture(LoadRosMap(yaml).grid), "???\n");
}

TEST(RosMapIo, NegateMakesDarkPixelsFree) {
  test::TempDir dir;
  dir.Write("m.pgm", Pgm({{0, 255, 128}}));
  const RosMap map = LoadRosMap(dir.Write("m.yaml", Replace(Yaml("m.pgm"), "negate: 0", "negate: true")));
  EXPECT_TRUE(map.metadata.thresholds.negate);
  EXPECT_EQ(test::Picture(map.grid), ".#?\n");
}

// In trinary mode map_server averages alpha in with the colours; in scale
// mode it leaves alpha out. A transparent white pixel tells them apart:
// trinary mean (3*255 + 0) / 4 -> p = 0.25 (unknown); scale mean 255 -> free.
TEST(RosMapIo, AlphaIsAveragedInTrinaryModeOnly) {
  test::TempDir dir;
  cv::Mat image(1, 2, CV_8UC4);
  image.at<cv::Vec4b>(0, 0) = {255, 255, 255, 0};    // transparent white
  image.at<cv::Vec4b>(0, 1) = {255, 255, 255, 255};  // opaque white
  ASSERT_TRUE(cv::imwrite(dir.Path("m.png"), image));
  EXPECT_EQ(test::Picture(LoadRosMap(dir.Write("t.yaml", Yaml("m.png"))).grid), "?.\n");
  EXPECT_EQ(test::Picture(LoadRosMap(dir.Write("s.yaml", Yaml("m.png", "mode: scale\n"))).grid), "..\n");
}

TEST(RosMapIo, ColourPixelsUseTheMeanOfTheirChannels) {
  test::TempDir dir;
  cv::Mat image(1, 2, CV_8UC3);
  image.at<cv::Vec3b>(0, 0) = {255, 255, 0};  // mean 170 -> p = 1/3: unknown
  image.at<cv::Vec3b>(0, 1) = {255, 0, 0};    // mean 85 -> p = 2/3: occupied
  ASSERT_TRUE(cv::imwrite(dir.Path("m.png"), image));
  EXPECT_EQ(test::Picture(LoadRosMap(dir.Write("m.yaml", Yaml("m.png"))).grid), "?#\n");
}

TEST(RosMapIo, ScaleModePartialOccupancyBecomesUnknown) {
  test::TempDir dir;
  dir.Write("m.pgm", Pgm({{254, 128, 0}}));
  const RosMap map = LoadRosMap(dir.Write("m.yaml", Yaml("m.pgm", "mode: scale\n")));
  EXPECT_EQ(map.metadata.mode, ImageMapMode::kScale);
  EXPECT_EQ(test::Picture(map.grid), ".?#\n");
}

TEST(RosMapIo, RawModeReadsOccupancyPercentages) {
  test::TempDir dir;
  dir.Write("m.pgm", Pgm({{0, 19, 50, 66, 100, 255}}));
  const RosMap map = LoadRosMap(dir.Write("m.yaml", Yaml("m.pgm", "mode: raw\n")));
  EXPECT_EQ(test::Picture(map.grid), "..?##?\n");
}

TEST(RosMapIo, RawModeRejectsValuesThatAreNotPercentages) {
  test::TempDir dir;
  const std::string image = dir.Write("m.pgm", Pgm({{0, 0}, {0, 254}}));
  const std::string yaml = dir.Write("m.yaml", Yaml("m.pgm", "mode: raw\n"));
  const InputError e = test::InputErrorFrom([&] { LoadRosMap(yaml); }, yaml);
  EXPECT_EQ(e.file(), yaml);
  EXPECT_EQ(e.field(), "image");
  EXPECT_NE(std::string(e.what()).find(image + ": field 'pixel (row 1, column 1)'"), std::string::npos) << e.what();
}

TEST(RosMapIo, SaveThenLoadGivesTheSameGridAndOrigin) {
  test::TempDir dir;
  OccupancyGrid grid(7, 4, 0.1, CellState::kFree);
  grid.Set(0, 0, CellState::kOccupied);
  grid.Set(6, 3, CellState::kUnknown);
  grid.Set(2, 1, CellState::kOccupied);
  grid.Set(5, 0, CellState::kUnknown);
  RosMapSaveOptions options;
  options.origin_x_m = -3.25;
  options.origin_y_m = 0.1;
  options.origin_yaw_rad = -0.7;
  const std::string yaml = dir.Path("saved.yaml");
  SaveRosMap(grid, yaml, options);

  const RosMap loaded = LoadRosMap(yaml);
  EXPECT_EQ(test::Picture(loaded.grid), test::Picture(grid));
  EXPECT_TRUE(loaded.grid.cells() == grid.cells());
  EXPECT_DOUBLE_EQ(loaded.grid.resolution_m(), 0.1);
  EXPECT_DOUBLE_EQ(loaded.metadata.origin_x_m, -3.25);
  EXPECT_DOUBLE_EQ(loaded.metadata.origin_y_m, 0.1);
  EXPECT_DOUBLE_EQ(loaded.metadata.origin_yaw_rad, -0.7);
  EXPECT_EQ(loaded.metadata.image_path, dir.Path("saved.pgm"));

  // map_saver's grey levels, top row first; no temporary file left behind.
  std::ifstream pgm(dir.Path("saved.pgm"), std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(pgm)), std::istreambuf_iterator<char>());
  ASSERT_EQ(bytes.substr(0, 3), "P5\n");
  const std::string pixels = bytes.substr(bytes.size() - 28);
  EXPECT_EQ(static_cast<unsigned char>(pixels[6]), 205);   // (6, 3): top row, last column
  EXPECT_EQ(static_cast<unsigned char>(pixels[21]), 0);    // (0, 0): bottom row, first column
  EXPECT_EQ(static_cast<unsigned char>(pixels[22]), 254);  // (1, 0)
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), std::filesystem::directory_iterator()), 2);
}

TEST(RosMapIo, SaveUsesTheGivenImageNameAndRejectsFolders) {
  test::TempDir dir;
  const OccupancyGrid grid(2, 2, 0.05);
  RosMapSaveOptions options;
  options.image_file_name = "picture.pgm";
  SaveRosMap(grid, dir.Path("a.yaml"), options);
  EXPECT_TRUE(std::filesystem::exists(dir.Path("picture.pgm")));
  options.image_file_name = "../picture.pgm";
  EXPECT_THROW(SaveRosMap(grid, dir.Path("b.yaml"), options), std::invalid_argument);
  options.image_file_name = "";
  options.origin_x_m = std::nan("");
  EXPECT_THROW(SaveRosMap(grid, dir.Path("c.yaml"), options), std::invalid_argument);
}

// A malformed YAML (content) with the m.pgm beside it.
using YamlCase = test::MalformedCase;

// Yaml("m.pgm") puts image on line 1, resolution 2, origin 3, negate 4,
// occupied_thresh 5, free_thresh 6; extra lines start at 7.
const std::string kGood = Yaml("m.pgm");

const YamlCase kRosMapMalformedCases[] = {
    YamlCase{"missing_resolution", Replace(kGood, "resolution: 0.05\n", ""), 0, "resolution", "missing required key"},
    YamlCase{"missing_image", Replace(kGood, "image: m.pgm\n", ""), 0, "image", "missing"},
    YamlCase{"missing_negate", Replace(kGood, "negate: 0\n", ""), 0, "negate", "missing"},
    YamlCase{"missing_free_thresh", Replace(kGood, "free_thresh: 0.196\n", ""), 0, "free_thresh", "missing"},
    YamlCase{"empty_resolution", Replace(kGood, "resolution: 0.05", "resolution:"), 2, "resolution", "has no value"},
    YamlCase{"zero_resolution", Replace(kGood, "0.05", "0"), 2, "resolution", "must be positive"},
    YamlCase{"negative_resolution", Replace(kGood, "0.05", "-0.05"), 2, "resolution", "must be positive"},
    YamlCase{"nan_resolution", Replace(kGood, "0.05", ".nan"), 2, "resolution", "not finite"},
    YamlCase{"inf_resolution", Replace(kGood, "0.05", ".inf"), 2, "resolution", "not finite"},
    YamlCase{"text_resolution", Replace(kGood, "0.05", "fine"), 2, "resolution", "'fine' is not a number"},
    YamlCase{"list_resolution", Replace(kGood, "0.05", "[0.05]"), 2, "resolution", "expected a number"},
    YamlCase{"short_origin", Replace(kGood, "[-1.5, 2.25, 0.3]", "[-1.5, 2.25]"), 3, "origin", "three numbers"},
    YamlCase{"scalar_origin", Replace(kGood, "[-1.5, 2.25, 0.3]", "0"), 3, "origin", "three numbers"},
    YamlCase{"nan_in_origin", Replace(kGood, "[-1.5, 2.25, 0.3]", "[-1.5, .NaN, 0.3]"), 3, "origin[1]", "not finite"},
    YamlCase{"origin_on_its_own_lines", Replace(kGood, "[-1.5, 2.25, 0.3]", "\n  - 0\n  - 0\n  - yaw"), 6, "origin[2]",
             "'yaw' is not a number"},
    YamlCase{"free_above_occupied", Replace(kGood, "free_thresh: 0.196", "free_thresh: 0.7"), 6, "free_thresh",
             "must be below occupied_thresh"},
    YamlCase{"free_equals_occupied", Replace(kGood, "free_thresh: 0.196", "free_thresh: 0.65"), 6, "free_thresh",
             "must be below occupied_thresh"},
    YamlCase{"occupied_above_one", Replace(kGood, "occupied_thresh: 0.65", "occupied_thresh: 1.5"), 5,
             "occupied_thresh", "in [0, 1]"},
    YamlCase{"free_negative", Replace(kGood, "free_thresh: 0.196", "free_thresh: -0.1"), 6, "free_thresh", "in [0, 1]"},
    YamlCase{"nan_threshold", Replace(kGood, "occupied_thresh: 0.65", "occupied_thresh: .nan"), 5, "occupied_thresh",
             "not finite"},
    YamlCase{"negate_two", Replace(kGood, "negate: 0", "negate: 2"), 4, "negate", "not 0, 1, false or true"},
    YamlCase{"negate_word", Replace(kGood, "negate: 0", "negate: maybe"), 4, "negate", "not 0, 1, false or true"},
    YamlCase{"unknown_mode", kGood + "mode: fancy\n", 7, "mode", "not trinary, scale or raw"},
    YamlCase{"raw_with_negate", Replace(kGood, "negate: 0", "negate: 1") + "mode: raw\n", 4, "negate", "raw mode"},
    YamlCase{"misspelt_key", kGood + "mdoe: scale\n", 7, "mdoe", "unknown key"},
    YamlCase{"duplicate_key", kGood + "resolution: 0.1\n", 7, "resolution", "appears twice"},
    YamlCase{"empty_image", Replace(kGood, "image: m.pgm", "image: ''"), 1, "image", "is empty"},
    YamlCase{"missing_image_file", Replace(kGood, "m.pgm", "absent.pgm"), 1, "image", "does not exist"},
    YamlCase{"syntax_error", Replace(kGood, "[-1.5, 2.25, 0.3]", "[-1.5, 2.25, 0.3"), 4, "", "YAML syntax error"},
    YamlCase{"not_a_mapping", "- image\n- resolution\n", 1, "", "expected a mapping"},
    YamlCase{"empty_file", "", 0, "", "expected a mapping"}};

TEST(RosMapIo, ThrowsInputErrorNamingTheYamlLineAndKey) {
  for (const YamlCase& c : kRosMapMalformedCases) {
    SCOPED_TRACE(c.name);
    test::TempDir dir;
    dir.Write("m.pgm", Pgm({{0, 254}}));
    const std::string yaml = dir.Write("m.yaml", c.content);
    EXPECT_EQ(test::InputErrorFrom([&] { LoadRosMap(yaml); }, c.content).file(), yaml);
    EXPECT_TRUE(ThrowsInputError([&] { LoadRosMap(yaml); }, c.line, c.field, c.problem));
  }
}

TEST(RosMapIo, MissingYamlFileIsAnInputError) {
  EXPECT_TRUE(ThrowsInputError([] { LoadRosMap("/nonexistent/map.yaml"); }, 0, "", "cannot open"));
}

// The image's own error comes behind the YAML's image key: the user named
// the YAML and may not know which image it pulls in.
TEST(RosMapIo, UndecodableImageIsAnInputErrorNamingTheYamlAndTheImage) {
  test::TempDir dir;
  const std::string image = dir.Write("m.pgm", "this is not an image\n");
  const std::string yaml = dir.Write("m.yaml", Yaml("m.pgm"));
  test::ExpectInputError([&] { LoadRosMap(yaml); }, yaml, 1, "image");
  const InputError e = test::InputErrorFrom([&] { LoadRosMap(yaml); }, yaml);
  EXPECT_NE(std::string(e.what()).find(image + ": not a PNG"), std::string::npos) << e.what();
}

// Review findings: a P2 sample above maxval loaded as free space, and a
// short raster gave "cannot decode" (after OpenCV's own message on stderr)
// without a field or the YAML. image_map_loader_test.cc covers every PNM
// defect; these check the message through the YAML.
TEST(RosMapIo, MalformedPgmIsLocatedInTheImageBehindTheYamlKey) {
  test::TempDir dir;
  const std::string image = dir.Write("m.pgm", "P2\n2 1\n100\n254 254\n");
  const std::string yaml = dir.Write("m.yaml", Yaml("m.pgm"));
  testing::internal::CaptureStderr();
  EXPECT_TRUE(
      ThrowsInputError([&] { LoadRosMap(yaml); }, 1, "image",
                       image + ":4: field 'pixel (row 0, column 0)': value 254 is above the header's maxval 100"));
  dir.Write("m.pgm", "P2\n10 10\n255\n0 0 0 0 0 0 0 0 0 0\n0 0 0 0 0 0 0 0 0 0\n");
  EXPECT_TRUE(
      ThrowsInputError([&] { LoadRosMap(yaml); }, 1, "image", image + ": field 'pixels': 20 of 100 values present"));
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
}

TEST(RosMapIo, ADirectoryGivenAsTheYamlOrTheImageIsAnInputError) {
  test::TempDir dir;
  const std::string folder = dir.Path("maps.yaml");
  std::filesystem::create_directory(folder);
  test::ExpectInputError([&] { LoadRosMap(folder); }, folder, 0, "");
  EXPECT_TRUE(ThrowsInputError([&] { LoadRosMap(folder); }, 0, "", "is a directory, not a file"));

  std::filesystem::create_directory(dir.Path("images"));
  const std::string yaml = dir.Write("m.yaml", Yaml("images"));
  EXPECT_TRUE(
      ThrowsInputError([&] { LoadRosMap(yaml); }, 1, "image", dir.Path("images") + ": is a directory, not a file"));
}

}  // namespace
}  // namespace rc
