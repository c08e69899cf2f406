#include "maps/image_map_loader.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <zlib.h>

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

// SmallImage as the bytes of a PNG file.
std::string SmallPng() {
  std::vector<unsigned char> encoded;
  if (!cv::imencode(".png", SmallImage(), encoded)) throw std::runtime_error("OpenCV cannot encode a PNG");
  return std::string(encoded.begin(), encoded.end());
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
  EXPECT_TRUE(ThrowsInputError([&] { LoadImageMap(cut, o); }, 0, "IHDR", "the first chunk is 'cate', not IHDR"));
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

TEST(ImageMapLoader, ADirectoryIsAnInputErrorNamingIt) {
  test::TempDir dir;
  ImageMapOptions o;
  o.resolution_m = 0.1;
  const std::string folder = dir.Path("walls.pgm");
  std::filesystem::create_directory(folder);
  test::ExpectInputError([&] { LoadImageMap(folder, o); }, folder, 0, "");
  EXPECT_TRUE(ThrowsInputError([&] { LoadImageMap(folder, o); }, 0, "", "is a directory, not a file"));
}

// Review findings: OpenCV clamped a plain sample above maxval (a P2 with
// maxval 100 and samples of 254 loaded as all free), reported a bad header
// or a short raster only as "cannot decode", and printed its own message on
// stderr first. Each PNM defect is now an InputError at its line and field.
const std::vector<test::MalformedCase> kMalformedPnms = {
    {"p2_sample_above_maxval", "P2\n2 1\n100\n0 254\n", 4, "pixel (row 0, column 1)",
     "value 254 is above the header's maxval 100"},
    {"p3_sample_above_maxval", "P3\n1 2\n200\n0 0 0\n0 0 201\n", 5, "pixel (row 1, column 0)", "above"},
    {"line_counts_comments", "P2\n# a\n# b\n2 1\n100\n0 101\n", 6, "pixel (row 0, column 1)", "above"},
    {"p2_too_few_values", "P2\n3 2\n255\n0 0 0\n0\n", 0, "pixels", "4 of 6 values present"},
    {"p2_too_many_values", "P2\n2 1\n255\n0 0\n0\n", 5, "pixels", "more than the 2 values of 2 x 1 pixels"},
    {"p2_no_line_break_at_the_end", "P2\n2 1\n255\n0\n255", 5, "pixels", "ends right after the last value"},
    {"p2_sample_not_a_number", "P2\n2 1\n255\n0 x\n", 4, "pixel (row 0, column 1)", "'x' is not a whole number"},
    {"p2_negative_sample", "P2\n2 1\n255\n0 -1\n", 4, "pixel (row 0, column 1)", "'-1' is not a whole number"},
    {"p1_digit_not_a_bit", "P1\n3 1\n102\n", 3, "pixel (row 0, column 2)", "'2' is not 0 or 1"},
    {"p5_truncated", "P5\n3 2\n255\n\x01\x02\x03", 0, "pixels", "3 of 6 raster bytes present"},
    {"p5_header_only", "P5\n3 2\n255", 0, "pixels", "0 of 6 raster bytes present"},
    {"p4_truncated", std::string("P4\n9 2\n\0\0\0", 10), 0, "pixels", "3 of 4 raster bytes present"},
    {"p6_truncated", "P6\n1 1\n255\n\x01\x02", 0, "pixels", "2 of 3 raster bytes present"},
    {"p5_trailing_bytes", "P5\n2 1\n255\n\x01\x02\x03", 0, "pixels", "1 byte follows the raster of 2 x 1 pixels"},
    {"p5_crlf_header", "P5\r\n2 1\r\n255\r\n\x01\x02", 0, "pixels", "the header ends in CR LF"},
    {"maxval_zero", "P2\n20 20\n0\n", 3, "maxval", "must be in [1, 65535], got 0"},
    {"maxval_above_netpbm", "P2\n20 20\n70000\n", 3, "maxval", "must be in [1, 65535], got 70000"},
    {"maxval_sixteen_bit", "P5\n1 1\n1000\n\x01\x02", 3, "maxval", "16-bit samples"},
    {"binary_maxval_below_255", "P5\n1 1\n100\n\x01", 3, "maxval", "save it with maxval 255"},
    {"width_zero", "P2\n0 20\n255\n", 2, "width", "got 0"},
    {"width_negative", "P2\n-5 20\n255\n", 2, "width", "'-5' is not a whole number"},
    {"height_missing", "P2\n5", 2, "height", "the file ends before the height"},
    {"height_huge", "P2\n5 99999999999999999999\n255\n", 2, "height", "must be in [1, 100000] pixels"},
    {"too_many_cells", "P5\n100000 100000\n255\n", 2, "width x height", "exceeds the limit"},
    {"maxval_glued_to_raster", "P5\n1 1\n255\x01", 3, "maxval", "'255?' is not a whole number"},
};

TEST(ImageMapLoader, MalformedPnmsAreInputErrorsAtTheirLineAndField) {
  ImageMapOptions o;
  o.resolution_m = 0.1;
  testing::internal::CaptureStderr();
  test::ExpectEveryCaseRefused(kMalformedPnms, "m.pgm", [&](const std::string& path) { LoadImageMap(path, o); });
  // None reached OpenCV's decoder, which prints its own message first.
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
}

TEST(ImageMapLoader, WellFormedPnmsOfEveryTypeLoad) {
  test::TempDir dir;
  ImageMapOptions o;
  o.resolution_m = 0.1;
  auto picture = [&](const std::string& content) {
    return test::Picture(LoadImageMap(dir.Write("m.pnm", content), o));
  };
  // Comments anywhere in the header; a plain raster ends in white space.
  EXPECT_EQ(picture("P2\n# made by hand\n3 1 # size\n255\n0 255 128 "), "#.?\n");
  // A plain maxval below 255 scales samples by 255 / maxval, as map_server does.
  EXPECT_EQ(picture("P2\n3 1\n100\n0 50 100\n"), "#?.\n");
  EXPECT_EQ(picture("P1\n3 1\n100\n"), "#..\n");  // 1 is black
  EXPECT_EQ(picture(std::string("P4\n3 1\n\x80", 8)), "#..\n");
  EXPECT_EQ(picture("P3\n2 1\n255\n0 0 0 255 255 255\n"), "#.\n");
  EXPECT_EQ(picture(std::string("P6\n2 1\n255\n\xff\xff\xff\0\0\0", 17)), ".#\n");
  EXPECT_EQ(picture(std::string("P5\n2 2\n255\n\0\xff\xff\0", 15)), "#.\n.#\n");
}

// A truncated or corrupt PNG made libpng print "libpng error: Read Error"
// (or a CRC error) on stderr before our "cannot decode". Its chunks are now
// checked first (maps/image_png_check.h): every prefix of a PNG and every
// byte changed after the signature is an InputError naming the chunk, and
// nothing else is printed.
TEST(ImageMapLoader, TruncatedOrCorruptPngsAreInputErrorsAndLibpngStaysQuiet) {
  test::TempDir dir;
  ImageMapOptions o;
  o.resolution_m = 0.1;
  const std::string png = SmallPng();
  const std::string path = dir.Path("m.png");
  testing::internal::CaptureStderr();
  for (std::size_t size = 8; size < png.size(); ++size) {
    dir.Write("m.png", png.substr(0, size));
    const InputError e = test::InputErrorFrom([&] { LoadImageMap(path, o); }, "the first " + std::to_string(size));
    EXPECT_NE(std::string(e.what()).find("truncated"), std::string::npos) << e.what();
    EXPECT_EQ(e.file(), path);
  }
  for (std::size_t at = 8; at < png.size(); ++at) {
    std::string corrupt = png;
    corrupt[at] = static_cast<char>(corrupt[at] ^ 0x10);
    dir.Write("m.png", corrupt);
    test::InputErrorFrom([&] { LoadImageMap(path, o); }, "byte " + std::to_string(at) + " changed");
  }
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  dir.Write("m.png", png);
  EXPECT_EQ(test::Picture(LoadImageMap(path, o)), "#.?\n...\n");
}

TEST(ImageMapLoader, PngDefectsNameTheChunk) {
  test::TempDir dir;
  ImageMapOptions o;
  o.resolution_m = 0.1;
  const std::string png = SmallPng();
  // IHDR is the 25 bytes after the signature; its data starts at byte 16.
  ASSERT_EQ(png.substr(12, 4), "IHDR");
  const std::size_t iend = png.rfind("IEND") - 4;
  const std::size_t idat = png.find("IDAT") - 4;
  ASSERT_EQ(iend + 12, png.size());
  auto load = [&](const std::string& content) {
    const std::string path = dir.Write("m.png", content);
    return [&o, path] { LoadImageMap(path, o); };
  };
  EXPECT_TRUE(ThrowsInputError(load(png.substr(0, iend)), 0, "IEND", "truncated: the file ends after chunk "));
  EXPECT_TRUE(ThrowsInputError(load(png.substr(0, idat + 10)), 0, "IDAT", "inside the chunk"));
  std::string flipped = png;
  flipped[idat + 8] = static_cast<char>(flipped[idat + 8] ^ 1);  // the first data byte
  EXPECT_TRUE(ThrowsInputError(load(flipped), 0, "IDAT", "CRC mismatch"));
  std::string no_idat = png.substr(0, 33) + png.substr(iend);
  EXPECT_TRUE(ThrowsInputError(load(no_idat), 0, "IEND", "before any IDAT"));
  // Bytes after IEND are ignored, as libpng ignores them.
  EXPECT_EQ(test::Picture(LoadImageMap(dir.Write("m.png", png + "trailing"), o)), "#.?\n...\n");
}

// A PNG chunk: length, type, data and a CRC that matches, so that the
// image data's check, not the CRC's, has to find what is wrong.
std::string Chunk(const std::string& type, const std::string& data) {
  std::string out;
  for (int shift = 24; shift >= 0; shift -= 8) out += static_cast<char>((data.size() >> shift) & 0xff);
  out += type + data;
  uLong crc = crc32_z(0L, Z_NULL, 0);
  crc = crc32_z(crc, reinterpret_cast<const Bytef*>(type.data()), type.size());
  crc = crc32_z(crc, reinterpret_cast<const Bytef*>(data.data()), data.size());
  for (int shift = 24; shift >= 0; shift -= 8) out += static_cast<char>((crc >> shift) & 0xff);
  return out;
}

std::string Deflate(const std::string& raw) {
  std::string out(compressBound(raw.size()), '\0');
  uLongf size = out.size();
  if (compress(reinterpret_cast<Bytef*>(out.data()), &size, reinterpret_cast<const Bytef*>(raw.data()), raw.size()) !=
      Z_OK)
    throw std::runtime_error("zlib cannot compress");
  out.resize(size);
  return out;
}

// An 8-bit grey PNG of `width` x `height` whose IDAT holds `idat` (or
// another bit depth and colour type, IHDR's two bytes).
std::string GreyPng(std::uint32_t width, std::uint32_t height, bool interlaced, const std::string& idat,
                    const std::string& depth_and_colour = std::string("\x08\x00", 2)) {
  std::string header;
  for (std::uint32_t v : {width, height})
    for (int shift = 24; shift >= 0; shift -= 8) header += static_cast<char>((v >> shift) & 0xff);
  header += depth_and_colour + std::string("\x00\x00", 2) + static_cast<char>(interlaced ? 1 : 0);
  return std::string("\x89PNG\r\n\x1a\n", 8) + Chunk("IHDR", header) + Chunk("IDAT", idat) + Chunk("IEND", "");
}

// SmallImage's scanlines, filter type 0: rows of 3 grey bytes.
const std::string kSmallRows = std::string("\0\x00\xff\x80\0\xff\xff\xff", 8);

TEST(ImageMapLoader, PngImageDataIsInflatedAndCheckedBeforeLibpngSeesIt) {
  test::TempDir dir;
  ImageMapOptions o;
  o.resolution_m = 0.1;
  auto load = [&](const std::string& content) {
    const std::string path = dir.Write("m.png", content);
    return [&o, path] { LoadImageMap(path, o); };
  };
  testing::internal::CaptureStderr();
  // Sound chunks around a sound stream: read.
  EXPECT_EQ(test::Picture(LoadImageMap(dir.Write("m.png", GreyPng(3, 2, false, Deflate(kSmallRows))), o)),
            "#.?\n...\n");
  // Sound chunks (their CRCs match) around bad image data.
  EXPECT_TRUE(ThrowsInputError(load(GreyPng(3, 2, false, "not a zlib stream")), 0, "IDAT", "cannot inflate"));
  std::string bad_filter = kSmallRows;
  bad_filter[4] = 7;  // the second scanline's filter type
  EXPECT_TRUE(
      ThrowsInputError(load(GreyPng(3, 2, false, Deflate(bad_filter))), 0, "IDAT", "scanline 1 has filter type 7"));
  EXPECT_TRUE(ThrowsInputError(load(GreyPng(3, 2, false, Deflate(kSmallRows.substr(0, 6)))), 0, "IDAT",
                               "inflates to 6 bytes; IHDR's size needs 8"));
  EXPECT_TRUE(ThrowsInputError(load(GreyPng(3, 2, false, Deflate(kSmallRows + std::string(1, '\0')))), 0, "IDAT",
                               "more than the 8 bytes"));
  const std::string stream = Deflate(kSmallRows);
  EXPECT_TRUE(
      ThrowsInputError(load(GreyPng(3, 2, false, stream.substr(0, stream.size() - 4))), 0, "IDAT", "does not end"));
  std::string wrong_check = stream;
  wrong_check.back() = static_cast<char>(wrong_check.back() ^ 1);  // the Adler-32's last byte
  EXPECT_TRUE(ThrowsInputError(load(GreyPng(3, 2, false, wrong_check)), 0, "IDAT", "cannot inflate"));
  EXPECT_TRUE(ThrowsInputError(load(GreyPng(3, 2, false, stream + "x")), 0, "IDAT", "after the end"));
  // The largest size IHDR allows, 16-bit RGBA: about 2^68 bytes.
  EXPECT_TRUE(ThrowsInputError(load(GreyPng(0x7fffffff, 0x7fffffff, false, stream, std::string("\x10\x06", 2))), 0,
                               "IHDR", "more than 2^62 bytes of image data"));
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
}

// Adam7 (PNG section 8.2) splits a 3 x 2 image into passes 1 (pixel 0,0),
// 4 (pixel 2,0), 6 (pixel 1,0) and 7 (row 1), each a scanline with its
// filter byte; passes 2, 3 and 5 are empty and have no scanline at all.
TEST(ImageMapLoader, InterlacedPngsAreCheckedPassByPassAndRead) {
  test::TempDir dir;
  ImageMapOptions o;
  o.resolution_m = 0.1;
  const std::string passes =
      std::string("\0\x00", 2) + std::string("\0\x80", 2) + std::string("\0\xff", 2) + std::string("\0\xff\xff\xff", 4);
  testing::internal::CaptureStderr();
  EXPECT_EQ(test::Picture(LoadImageMap(dir.Write("m.png", GreyPng(3, 2, true, Deflate(passes))), o)), "#.?\n...\n");
  std::string bad = passes;
  bad[6] = 5;  // pass 7's filter type
  const std::string path = dir.Write("m.png", GreyPng(3, 2, true, Deflate(bad)));
  EXPECT_TRUE(ThrowsInputError([&] { LoadImageMap(path, o); }, 0, "IDAT", "scanline 0 of pass 7 has filter type 5"));
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
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
