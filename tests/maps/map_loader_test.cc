#include "maps/map_loader.h"

#include <filesystem>

#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "map_test_util.h"
#include "support/input_error_expectations.h"
#include "support/temp_dir.h"

namespace rc {
namespace {

using test::ThrowsInputError;

const char kCmu[] =
    "robot_specifications->global_mapsize_x 20\n"
    "robot_specifications->global_mapsize_y 10\n"
    "robot_specifications->resolution 10\n"
    "\n"
    "global_map[0]: 2 1\n"
    "1.0\n"
    "0.0\n";
const char kRowild[] = "mapsize_x 20\nmapsize_y 10\nresolution 10\n1.0\n0.0\n";
const char kMovingAi[] = "type octile\nheight 1\nwidth 2\nmap\n.@\n";

TEST(MapLoader, DatFilesAreToldApartByTheirFirstLine) {
  test::TempDir dir;
  const LoadedMap cmu = LoadMap(dir.Write("a.dat", kCmu));
  EXPECT_EQ(cmu.format, "cmu");
  EXPECT_EQ(cmu.grid.At(0, 0), CellState::kFree);
  EXPECT_EQ(cmu.grid.At(1, 0), CellState::kOccupied);
  EXPECT_NE(cmu.value_convention.find("P(free)"), std::string::npos);
  EXPECT_FALSE(cmu.ros.has_value());

  const LoadedMap rowild = LoadMap(dir.Write("b.dat", kRowild));
  EXPECT_EQ(rowild.format, "rowild");
  EXPECT_TRUE(rowild.grid.cells() == cmu.grid.cells());
}

TEST(MapLoader, ConventionOptionReachesProbabilityLoaders) {
  test::TempDir dir;
  MapLoadOptions o;
  o.convention = ValueConvention::kProbabilityOccupied;
  const LoadedMap m = LoadMap(dir.Write("b.dat", kRowild), o);
  EXPECT_EQ(m.grid.At(0, 0), CellState::kOccupied);
  EXPECT_NE(m.value_convention.find("P(occupied)"), std::string::npos);
}

TEST(MapLoader, DispatchesYamlMapAndImagesByExtension) {
  test::TempDir dir;
  cv::Mat image(1, 2, CV_8UC1, cv::Scalar(0));
  image.at<std::uint8_t>(0, 1) = 254;
  ASSERT_TRUE(cv::imwrite(dir.Path("m.pgm"), image));
  ASSERT_TRUE(cv::imwrite(dir.Path("m.png"), image));
  const std::string yaml = dir.Write("m.yml",
                                     "image: m.pgm\nresolution: 0.5\norigin: [1, 2, 0]\nnegate: 0\n"
                                     "occupied_thresh: 0.65\nfree_thresh: 0.196\n");
  const LoadedMap ros = LoadMap(yaml);
  EXPECT_EQ(ros.format, "ros");
  ASSERT_TRUE(ros.ros.has_value());
  EXPECT_DOUBLE_EQ(ros.ros->origin_x_m, 1.0);
  EXPECT_EQ(test::Picture(ros.grid), "#.\n");
  EXPECT_NE(ros.value_convention.find("trinary"), std::string::npos);

  const LoadedMap movingai = LoadMap(dir.Write("m.map", kMovingAi));
  EXPECT_EQ(movingai.format, "movingai");
  EXPECT_DOUBLE_EQ(movingai.grid.resolution_m(), 1.0);
  EXPECT_EQ(test::Picture(movingai.grid), ".#\n");

  MapLoadOptions o;
  o.resolution_m = 0.05;
  for (const char* name : {"m.png", "m.pgm"}) {
    const LoadedMap img = LoadMap(dir.Path(name), o);
    EXPECT_EQ(img.format, "image");
    EXPECT_DOUBLE_EQ(img.grid.resolution_m(), 0.05);
    EXPECT_EQ(test::Picture(img.grid), "#.\n");
  }
}

TEST(MapLoader, ExtensionsAreCaseInsensitive) {
  test::TempDir dir;
  EXPECT_EQ(LoadMap(dir.Write("M.MAP", kMovingAi)).format, "movingai");
}

TEST(MapLoader, FormatOverrideIgnoresTheExtension) {
  test::TempDir dir;
  MapLoadOptions o;
  o.format = "movingai";
  o.resolution_m = 0.2;
  const LoadedMap m = LoadMap(dir.Write("grid.txt", kMovingAi), o);
  EXPECT_EQ(m.format, "movingai");
  EXPECT_DOUBLE_EQ(m.grid.resolution_m(), 0.2);
  o = {};
  o.format = "rowild";
  EXPECT_EQ(LoadMap(dir.Write("x.txt", kRowild), o).format, "rowild");
}

TEST(MapLoader, UnknownExtensionIsAnInputError) {
  test::TempDir dir;
  const auto path = dir.Write("m.txt", kMovingAi);
  EXPECT_TRUE(ThrowsInputError([&] { LoadMap(path); }, 0, "extension", "unknown map extension '.txt'"));
  const auto bare = dir.Write("noextension", kMovingAi);
  EXPECT_TRUE(ThrowsInputError([&] { LoadMap(bare); }, 0, "extension", "unknown map extension"));
}

TEST(MapLoader, DatWithAnotherHeaderIsAnInputError) {
  test::TempDir dir;
  const auto path = dir.Write("m.dat", "\n# comment\n1 2 3\n");
  EXPECT_TRUE(ThrowsInputError([&] { LoadMap(path); }, 2, "header", "must start with"));
  const auto empty = dir.Write("e.dat", "\n\n");
  EXPECT_TRUE(ThrowsInputError([&] { LoadMap(empty); }, 0, "header", "empty"));
}

// Notepad and other Windows editors start a UTF-8 file with a byte-order
// mark; it is not part of the first header line.
TEST(MapLoader, TextMapsMayStartWithAByteOrderMark) {
  test::TempDir dir;
  const std::string bom = "\xEF\xBB\xBF";
  const LoadedMap cmu = LoadMap(dir.Write("a.dat", bom + kCmu));
  EXPECT_EQ(cmu.format, "cmu");
  EXPECT_EQ(cmu.grid.At(1, 0), CellState::kOccupied);
  EXPECT_EQ(LoadMap(dir.Write("b.dat", bom + kRowild)).format, "rowild");
  MapLoadOptions cmu_format;
  cmu_format.format = "cmu";  // the loader itself, not only the format detection
  EXPECT_EQ(LoadMap(dir.Write("c.txt", bom + kCmu), cmu_format).grid.At(0, 0), CellState::kFree);
  EXPECT_EQ(LoadMap(dir.Write("m.map", bom + kMovingAi)).grid.At(1, 0), CellState::kOccupied);
}

TEST(MapLoader, ADirectoryIsNotAnEmptyMap) {
  test::TempDir dir;
  for (const char* name : {"d.dat", "d.map"}) {
    const std::string path = dir.Path(name);
    std::filesystem::create_directory(path);
    EXPECT_TRUE(ThrowsInputError([&] { LoadMap(path); }, 0, "", "is a directory, not a file")) << name;
    for (const char* format : {"cmu", "rowild", "movingai"}) {
      MapLoadOptions o;
      o.format = format;
      EXPECT_TRUE(ThrowsInputError([&] { LoadMap(path, o); }, 0, "", "is a directory")) << name << " " << format;
    }
  }
}

// strtod reads C99 hex floats; the map formats are decimal, as the ROS YAML.
TEST(MapLoader, HexadecimalCellValuesAreRefused) {
  test::TempDir dir;
  std::string cmu = kCmu;
  cmu.replace(cmu.find("0.0\n"), 3, "0x0");
  EXPECT_TRUE(ThrowsInputError([&] { LoadMap(dir.Write("a.dat", cmu)); }, 7, "map row 1, column 0", "hexadecimal"));
  std::string rowild = kRowild;
  rowild.replace(rowild.find("1.0\n"), 3, "0x1p-1");
  EXPECT_TRUE(ThrowsInputError([&] { LoadMap(dir.Write("b.dat", rowild)); }, 4, "map row 0, column 0", "hexadecimal"));
}

TEST(MapLoader, OptionsThatDoNotApplyAreRejected) {
  test::TempDir dir;
  const auto dat = dir.Write("b.dat", kRowild);
  const auto map = dir.Write("m.map", kMovingAi);
  MapLoadOptions o;
  o.resolution_m = 0.1;
  EXPECT_THROW(LoadMap(dat, o), UsageError);
  o = {};
  o.convention = ValueConvention::kProbabilityFree;
  EXPECT_THROW(LoadMap(map, o), UsageError);
  o = {};
  o.occupied_thresh = 0.65;
  EXPECT_THROW(LoadMap(map, o), UsageError);
  o = {};
  o.format = "octomap";
  EXPECT_THROW(LoadMap(map, o), UsageError);
}

TEST(MapLoader, ImageWithoutResolutionIsAUsageError) {
  test::TempDir dir;
  ASSERT_TRUE(cv::imwrite(dir.Path("m.png"), cv::Mat(1, 1, CV_8UC1, cv::Scalar(0))));
  EXPECT_THROW(LoadMap(dir.Path("m.png")), UsageError);
}

TEST(MapLoader, LoaderErrorsPassThrough) {
  test::TempDir dir;
  const auto path = dir.Write("m.map", "type octile\nheight 2\nwidth 2\nmap\n..\n");
  EXPECT_TRUE(ThrowsInputError([&] { LoadMap(path); }, 6, "map row 1", "file ends"));
}

}  // namespace
}  // namespace rc
