// A truncated or corrupt JPEG map made libjpeg print "Premature end of JPEG
// file" or "Corrupt JPEG data: ..." on stderr and decode the rest grey. The
// file is now decoded once by libjpeg under a quiet error manager first
// (maps/image_jpeg_check.h): these tests load JPEGs that OpenCV and libjpeg
// write, and expect every damaged one that libjpeg notices to be an
// InputError naming the stage, while nothing is printed.
#include "maps/image_jpeg_check.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>  // jpeglib.h uses FILE and size_t without including their headers
#include <cstdlib>
#include <functional>
#include <functional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include <jpeglib.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "map_test_util.h"
#include "maps/image_map_loader.h"
#include "support/input_error_expectations.h"
#include "support/temp_dir.h"

namespace rc {
namespace {

using test::ThrowsInputError;

constexpr int kSof0 = 0xC0, kSof2 = 0xC2, kSof9 = 0xC9, kSof10 = 0xCA, kSos = 0xDA, kDqt = 0xDB, kDri = 0xDD,
              kApp0 = 0xE0;

// 16 x 24 pixels in 8 x 8 blocks of one value each, which JPEG keeps close
// to exact: top row black, white, mid-grey; bottom row white.
cv::Mat BlockImage() {
  cv::Mat image(16, 24, CV_8UC1, cv::Scalar(255));
  image(cv::Rect(0, 0, 8, 8)).setTo(0);
  image(cv::Rect(16, 0, 8, 8)).setTo(128);
  return image;
}

// BlockImage as a grid picture (map_test_util.h): '#' black, '.' white,
// '?' grey; image row 0 is the top line.
std::string BlockPicture() {
  std::string top, bottom;
  for (int i = 0; i < 8; ++i) top += "########........????????\n";
  for (int i = 0; i < 8; ++i) bottom += "........................\n";
  return top + bottom;
}

std::string Jpeg(const cv::Mat& image, const std::vector<int>& params = {}) {
  std::vector<unsigned char> encoded;
  if (!cv::imencode(".jpg", image, encoded, params)) throw std::runtime_error("OpenCV cannot encode a JPEG");
  return std::string(encoded.begin(), encoded.end());
}

// An arithmetic-coded JPEG of a grey image, which OpenCV does not write:
// through libjpeg itself, as `cjpeg -arithmetic` would. libjpeg's default
// error handler would exit the process, but a sound image never errors.
std::string ArithmeticJpeg(const cv::Mat& grey, bool progressive) {
  jpeg_compress_struct c{};
  jpeg_error_mgr errors{};
  c.err = jpeg_std_error(&errors);
  jpeg_create_compress(&c);
  unsigned char* buffer = nullptr;
  unsigned long size = 0;
  jpeg_mem_dest(&c, &buffer, &size);
  c.image_width = static_cast<JDIMENSION>(grey.cols);
  c.image_height = static_cast<JDIMENSION>(grey.rows);
  c.input_components = 1;
  c.in_color_space = JCS_GRAYSCALE;
  jpeg_set_defaults(&c);
  jpeg_set_quality(&c, 95, TRUE);
  c.arith_code = TRUE;
  if (progressive) jpeg_simple_progression(&c);
  jpeg_start_compress(&c, TRUE);
  while (c.next_scanline < c.image_height) {
    JSAMPROW row = const_cast<JSAMPROW>(grey.ptr<JSAMPLE>(static_cast<int>(c.next_scanline)));
    jpeg_write_scanlines(&c, &row, 1);
  }
  jpeg_finish_compress(&c);
  jpeg_destroy_compress(&c);
  const std::string jpeg(reinterpret_cast<const char*>(buffer), size);
  std::free(buffer);
  return jpeg;
}

// Noise in colour: every Huffman code length, interleaved chroma.
cv::Mat NoiseImage() {
  cv::Mat image(37, 51, CV_8UC3);
  cv::RNG rng(7);
  rng.fill(image, cv::RNG::UNIFORM, 0, 256);
  return image;
}

ImageMapOptions Options() {
  ImageMapOptions o;
  o.resolution_m = 0.1;
  return o;
}

int Byte(const std::string& s, std::size_t i) { return static_cast<std::uint8_t>(s[i]); }

// The byte offset of the first segment with marker `code` before the scan
// data; npos when there is none.
std::size_t FindSegment(const std::string& jpeg, int code) {
  for (std::size_t i = 2; i + 4 <= jpeg.size() && Byte(jpeg, i) == 0xFF;) {
    if (Byte(jpeg, i + 1) == code) return i;
    if (Byte(jpeg, i + 1) == kSos) break;
    i += 2 + static_cast<std::size_t>((Byte(jpeg, i + 2) << 8) | Byte(jpeg, i + 3));
  }
  return std::string::npos;
}

// The whole segment at `at`: marker, length and data.
std::size_t SegmentSize(const std::string& jpeg, std::size_t at) {
  return 2 + static_cast<std::size_t>((Byte(jpeg, at + 2) << 8) | Byte(jpeg, at + 3));
}

TEST(ImageJpegCheck, JpegsThatOpenCvAndLibjpegWriteLoad) {
  const test::TempDir dir;
  const ImageMapOptions o = Options();
  const std::string baseline = Jpeg(BlockImage());
  EXPECT_EQ(test::Picture(LoadImageMap(dir.Write("m.jpg", baseline), o)), BlockPicture());
  cv::Mat colour;
  cv::merge(std::vector<cv::Mat>(3, BlockImage()), colour);
  EXPECT_EQ(test::Picture(LoadImageMap(dir.Write("c.jpg", Jpeg(colour)), o)), BlockPicture());
  const std::string progressive = Jpeg(BlockImage(), {cv::IMWRITE_JPEG_PROGRESSIVE, 1});
  ASSERT_NE(FindSegment(progressive, kSof2), std::string::npos);
  EXPECT_EQ(test::Picture(LoadImageMap(dir.Write("p.jpg", progressive), o)), BlockPicture());
  const std::string arithmetic = ArithmeticJpeg(BlockImage(), false);
  ASSERT_NE(FindSegment(arithmetic, kSof9), std::string::npos);
  EXPECT_EQ(test::Picture(LoadImageMap(dir.Write("a.jpg", arithmetic), o)), BlockPicture());
  const std::string arithmetic_progressive = ArithmeticJpeg(BlockImage(), true);
  ASSERT_NE(FindSegment(arithmetic_progressive, kSof10), std::string::npos);
  EXPECT_EQ(test::Picture(LoadImageMap(dir.Write("ap.jpg", arithmetic_progressive), o)), BlockPicture());
  // Bytes after EOI are ignored, as libjpeg ignores them.
  EXPECT_EQ(test::Picture(LoadImageMap(dir.Write("t.jpg", baseline + "trailing"), o)), BlockPicture());
  // Sequential and progressive, interleaved and not, with and without
  // restart intervals, default and optimized Huffman tables.
  const std::vector<std::vector<int>> settings = {
      {},
      {cv::IMWRITE_JPEG_OPTIMIZE, 1},
      {cv::IMWRITE_JPEG_RST_INTERVAL, 2},
      {cv::IMWRITE_JPEG_PROGRESSIVE, 1},
      {cv::IMWRITE_JPEG_PROGRESSIVE, 1, cv::IMWRITE_JPEG_RST_INTERVAL, 3},
      {cv::IMWRITE_JPEG_QUALITY, 20},
  };
  for (const std::vector<int>& params : settings) {
    const std::string path = dir.Write("n.jpg", Jpeg(NoiseImage(), params));
    EXPECT_NO_THROW(CheckJpegImage(path)) << testing::PrintToString(params);
    EXPECT_NO_THROW(LoadImageMap(path, o)) << testing::PrintToString(params);
  }
}

// Every prefix is refused as truncated: libjpeg reads on until the data
// runs out ("Premature end of JPEG file"; "Empty input file" for none),
// whatever stage it is in. The loader itself needs 3 bytes ("FF D8 FF") to
// take a file for a JPEG, so shorter ones go to the check directly.
TEST(ImageJpegCheck, EveryPrefixIsTruncatedAndLibjpegStaysQuiet) {
  const test::TempDir dir;
  const ImageMapOptions o = Options();
  const std::string path = dir.Path("m.jpg");
  const std::vector<std::string> files = {Jpeg(BlockImage()), Jpeg(NoiseImage(), {cv::IMWRITE_JPEG_PROGRESSIVE, 1}),
                                          ArithmeticJpeg(BlockImage(), false), ArithmeticJpeg(BlockImage(), true)};
  testing::internal::CaptureStderr();
  for (const std::string& jpeg : files) {
    std::set<std::string> fields;
    for (std::size_t size = 0; size < jpeg.size(); ++size) {
      dir.Write("m.jpg", jpeg.substr(0, size));
      const std::string what = "the first " + std::to_string(size) + " bytes";
      const InputError e = size < 3 ? test::InputErrorFrom([&] { CheckJpegImage(path); }, what)
                                    : test::InputErrorFrom([&] { LoadImageMap(path, o); }, what);
      const std::string message = e.what();
      EXPECT_NE(message.find(size == 0 ? "truncated: Empty input file" : "truncated: Premature end of JPEG file"),
                std::string::npos)
          << message;
      EXPECT_NE(message.find(" of " + std::to_string(size) + ")"), std::string::npos) << message;
      EXPECT_EQ(e.file(), path);
      fields.insert(e.field());
    }
    // Cut before the first scan's data, or in a scan's data: libjpeg's
    // read-ahead for the last MCU finds a missing EOI, so never "EOI".
    EXPECT_EQ(fields, (std::set<std::string>{"header", "scan data"}));
  }
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
}

// Any byte changed, in the headers or the scan data: the file loads (a
// changed value that a sound file may hold, or one libjpeg passes over
// silently) or is an InputError; nothing is printed.
TEST(ImageJpegCheck, ChangedBytesLoadOrAreInputErrorsAndLibjpegStaysQuiet) {
  const test::TempDir dir;
  const ImageMapOptions o = Options();
  const std::string path = dir.Path("m.jpg");
  for (const std::string& jpeg : {Jpeg(BlockImage()), Jpeg(BlockImage(), {cv::IMWRITE_JPEG_PROGRESSIVE, 1}),
                                  ArithmeticJpeg(BlockImage(), false)}) {
    int loaded = 0, refused = 0;
    testing::internal::CaptureStderr();
    for (std::size_t at = 2; at < jpeg.size(); ++at) {
      for (int mask : {0x01, 0x10, 0x80}) {
        std::string changed = jpeg;
        changed[at] = static_cast<char>(changed[at] ^ mask);
        dir.Write("m.jpg", changed);
        try {
          LoadImageMap(path, o);
          ++loaded;
        } catch (const InputError&) {
          ++refused;
        }
      }
    }
    EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
    EXPECT_GT(loaded, 0);
    EXPECT_GT(refused, 0);
  }
}

// A call that checks `content` written as m.jpg in `dir`.
std::function<void()> CheckOf(const test::TempDir& dir, const std::string& content) {
  const std::string path = dir.Write("m.jpg", content);
  return [path] { CheckJpegImage(path); };
}

TEST(ImageJpegCheck, DefectsNameTheStageAndTheByte) {
  const test::TempDir dir;
  const std::string jpeg = Jpeg(BlockImage());
  auto check = [&](const std::string& content) { return CheckOf(dir, content); };
  const std::size_t dqt = FindSegment(jpeg, kDqt), sof = FindSegment(jpeg, kSof0), sos = FindSegment(jpeg, kSos);
  ASSERT_NE(dqt, std::string::npos);
  ASSERT_NE(sof, std::string::npos);
  ASSERT_NE(sos, std::string::npos);
  const std::size_t data = sos + SegmentSize(jpeg, sos);

  // What libjpeg refuses. Without the check: silent, and no more to say
  // than "cannot decode".
  EXPECT_TRUE(ThrowsInputError(check(jpeg.substr(2)), 0, "header",
                               "Not a JPEG file: starts with 0xff 0xe0 (libjpeg was reading from byte 0 of"));
  std::string no_sof = jpeg;
  no_sof.erase(sof, SegmentSize(jpeg, sof));
  EXPECT_TRUE(ThrowsInputError(check(no_sof), 0, "header", "SOS before SOF"));
  std::string twelve_bit = jpeg;
  twelve_bit[sof + 4] = 12;
  EXPECT_TRUE(ThrowsInputError(check(twelve_bit), 0, "header", "Unsupported JPEG data precision 12"));
  std::string lossless = jpeg;
  lossless[sof + 1] = '\xc3';
  EXPECT_TRUE(ThrowsInputError(check(lossless), 0, "header", "Unsupported JPEG process: SOF type 0xc3"));
  std::string long_dqt = jpeg;
  long_dqt[dqt + 2] = '\xff';
  EXPECT_TRUE(ThrowsInputError(check(long_dqt), 0, "header", "Bogus DQT index 15"));
  std::string no_dqt = jpeg;
  no_dqt.erase(dqt, SegmentSize(jpeg, dqt));
  EXPECT_TRUE(ThrowsInputError(check(no_dqt), 0, "scan data", "Quantization table 0x00 was not defined"));
  // The map size limits, before libjpeg allocates for the size: 65000 x
  // 65000 pixels, within libjpeg's limit.
  std::string huge = jpeg;
  huge.replace(sof + 5, 4, "\xfd\xe8\xfd\xe8");
  EXPECT_TRUE(ThrowsInputError(check(huge), 0, "header", "map size 65000 x 65000 cells exceeds the limit"));

  // What libjpeg warns about on stderr, decoding on.
  std::string garbage = jpeg;
  garbage.insert(sof, "x");
  // Extraneous bytes are found at the marker that follows them.
  EXPECT_TRUE(
      ThrowsInputError(check(garbage), 0, "header",
                       "Corrupt JPEG data: 1 extraneous bytes before marker 0xc0 (libjpeg was reading from byte " +
                           std::to_string(sof + 1) + " of "));
  std::string jfif2 = jpeg;
  const std::size_t app0 = FindSegment(jpeg, kApp0);
  ASSERT_EQ(jpeg.substr(app0 + 4, 5), std::string("JFIF\0", 5));
  jfif2[app0 + 9] = 2;  // major version
  EXPECT_TRUE(ThrowsInputError(check(jfif2), 0, "header", "unknown JFIF revision number 2.01"));
  std::string not_sequential = jpeg;
  not_sequential[data - 2] = 62;  // Se
  EXPECT_TRUE(ThrowsInputError(check(not_sequential), 0, "scan data", "Invalid SOS parameters for sequential JPEG"));
  std::string extra = jpeg;
  extra.insert(jpeg.size() - 2, std::string(20, '\x55'));
  // 20 bytes before EOI: libjpeg's bit buffer takes in the first 3 unseen.
  EXPECT_TRUE(
      ThrowsInputError(check(extra), 0, "EOI",
                       "Corrupt JPEG data: 17 extraneous bytes before marker 0xd9 (libjpeg was reading from byte " +
                           std::to_string(extra.size() - 2) + " of "));
  std::string short_scan = jpeg;
  short_scan.erase(data + 1, 1);
  EXPECT_TRUE(ThrowsInputError(check(short_scan), 0, "scan data", "Corrupt JPEG data: premature end of data segment"));
  // Without EOI: libjpeg's read-ahead for the last MCU finds the end.
  EXPECT_TRUE(ThrowsInputError(check(jpeg.substr(0, jpeg.size() - 2)), 0, "scan data",
                               "truncated: Premature end of JPEG file (libjpeg was reading from byte "));
}

TEST(ImageJpegCheck, RestartMarkersFollowTheirInterval) {
  const test::TempDir dir;
  auto check = [&](const std::string& content) { return CheckOf(dir, content); };
  const std::string jpeg = Jpeg(NoiseImage(), {cv::IMWRITE_JPEG_RST_INTERVAL, 1});
  const std::size_t dri = FindSegment(jpeg, kDri), sos = FindSegment(jpeg, kSos);
  ASSERT_NE(dri, std::string::npos);
  const std::size_t rst0 = jpeg.find("\xff\xd0", sos), rst1 = jpeg.find("\xff\xd1", sos);
  ASSERT_NE(rst0, std::string::npos);
  ASSERT_NE(rst1, std::string::npos);
  std::string swapped = jpeg;
  swapped[rst0 + 1] = '\xd1';
  EXPECT_TRUE(ThrowsInputError(check(swapped), 0, "scan data", "found marker 0xd1 instead of RST0"));
  std::string no_dri = jpeg;
  no_dri.erase(dri, SegmentSize(jpeg, dri));
  EXPECT_TRUE(ThrowsInputError(check(no_dri), 0, "scan data", "Corrupt JPEG data: premature end of data segment"));
  std::string lost_interval = jpeg;
  lost_interval.erase(rst0, rst1 - rst0);  // RST0 and the interval after it
  EXPECT_TRUE(ThrowsInputError(check(lost_interval), 0, "scan data", "found marker 0xd1 instead of RST0"));
}

}  // namespace
}  // namespace rc
