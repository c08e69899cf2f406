#include "maps/image_pnm_check.h"

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <istream>

#include "common/input_error.h"
#include "maps/grid_size_limits.h"
#include "maps/image_occupancy.h"

namespace rc {
namespace {

constexpr int kEnd = std::char_traits<char>::eof();
constexpr long kMaxSample = 255;       // 8-bit samples only (image_occupancy.h)
constexpr long kNetpbmMaxval = 65535;  // Netpbm's own limit
// More digits than any valid number here needs; bounds a token's length so
// that a binary blob without white space is not read into one string.
constexpr std::size_t kMaxTokenChars = 24;
constexpr long kSaturated = 1L << 40;

bool IsSpace(int c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f'; }

// A token for a message: non-printable bytes as '?'.
std::string Shown(const std::string& token) {
  std::string out;
  for (char c : token) out += (c >= 0x20 && c < 0x7f) ? c : '?';
  return "'" + out + "'";
}

// The file as a stream of characters that knows its line and offset.
class PnmCursor {
 public:
  PnmCursor(std::streambuf* in, std::string path) : in_(in), path_(std::move(path)) {}

  int Peek() { return in_->sgetc(); }
  int Take() {
    const int c = in_->sbumpc();
    if (c == kEnd) return c;
    ++offset_;
    if (c == '\n') ++line_;
    return c;
  }

  // Skips white space and '#' comments (a comment ends at CR or LF).
  void SkipSpace() {
    for (int c = Peek(); c != kEnd; c = Peek()) {
      if (c == '#') {
        while (c != kEnd && c != '\n' && c != '\r') c = Take();
      } else if (IsSpace(c)) {
        Take();
      } else {
        return;
      }
    }
  }

  // The next run of non-space characters (empty at the end of the file);
  // token_line() is its line. A '#' inside a token is part of it: OpenCV
  // reads a comment only where a number would start.
  const std::string& Token() {
    SkipSpace();
    token_line_ = line_;
    token_.clear();
    for (int c = Peek(); c != kEnd && !IsSpace(c) && token_.size() < kMaxTokenChars; c = Peek())
      token_ += static_cast<char>(Take());
    return token_;
  }
  const std::string& token() const { return token_; }
  long token_line() const { return token_line_; }
  long line() const { return line_; }
  std::uint64_t offset() const { return offset_; }

  // The token as a whole number; false unless it is all digits. Saturates at
  // kSaturated, above every limit checked here; messages quote the token.
  static bool Whole(const std::string& token, long* value) {
    if (token.empty()) return false;
    *value = 0;
    for (char c : token) {
      if (c < '0' || c > '9') return false;
      *value = std::min(*value * 10 + (c - '0'), kSaturated);
    }
    return true;
  }

  // A header number: present and whole.
  long HeaderNumber(const std::string& field) {
    const std::string& token = Token();
    if (token.empty()) Fail(line_, field, "the file ends before the " + field);
    long value = 0;
    if (!Whole(token, &value)) Fail(token_line_, field, Shown(token) + " is not a whole number (digits only)");
    return value;
  }

  [[noreturn]] void Fail(long line, const std::string& field, const std::string& problem) const {
    throw InputError(path_, line, field, problem);
  }

 private:
  std::streambuf* in_;
  std::string path_;
  std::string token_;
  long line_ = 1;
  long token_line_ = 1;
  std::uint64_t offset_ = 0;
};

struct PnmHeader {
  int type = 0;  // the digit after 'P'
  long width = 0, height = 0;
  long maxval = 1;  // 1 for the bitmaps, which have none
  bool binary() const { return type >= 4; }
  bool bitmap() const { return type == 1 || type == 4; }
  int channels() const { return type == 3 || type == 6 ? 3 : 1; }
};

long SideLength(PnmCursor& in, const std::string& field) {
  const long value = in.HeaderNumber(field);
  if (value < 1 || value > kMaxMapCellsPerSide)
    in.Fail(in.token_line(), field,
            "must be in [1, " + std::to_string(kMaxMapCellsPerSide) + "] pixels, got " + in.token());
  return value;
}

PnmHeader ReadHeader(PnmCursor& in, const std::string& path) {
  PnmHeader h;
  const int p = in.Take(), digit = in.Take();
  if (p != 'P' || digit < '1' || digit > '6' || !IsSpace(in.Peek()))
    in.Fail(1, "magic", "not a Netpbm magic number (P1 to P6, then white space)");
  h.type = digit - '0';
  h.width = SideLength(in, "width");
  h.height = SideLength(in, "height");
  CheckMapSize(path, in.token_line(), "width x height", h.width, h.height);
  if (h.bitmap()) return h;
  h.maxval = in.HeaderNumber("maxval");
  const std::string& shown = in.token();
  if (h.maxval < 1 || h.maxval > kNetpbmMaxval)
    in.Fail(in.token_line(), "maxval", "must be in [1, " + std::to_string(kNetpbmMaxval) + "], got " + shown);
  if (h.maxval > kMaxSample)
    in.Fail(in.token_line(), "maxval",
            shown + " means 16-bit samples; only 8-bit images (maxval up to 255) are supported");
  if (h.binary() && h.maxval != kMaxSample)
    in.Fail(in.token_line(), "maxval",
            "a binary PGM or PPM with maxval " + shown +
                " is not supported: OpenCV would read its samples unscaled (map_server scales them by 255 / "
                "maxval); save it with maxval 255");
  return h;
}

void CheckBinaryRaster(PnmCursor& in, std::streambuf* file, const PnmHeader& h) {
  // One white-space character ends the header; the raster follows it.
  const long line = in.token_line();
  const int end_of_header = in.Take();
  if (end_of_header != kEnd && !IsSpace(end_of_header))
    in.Fail(line, h.bitmap() ? "height" : "maxval", "must be followed by one white-space character, then the raster");
  const bool crlf = end_of_header == '\r' && in.Peek() == '\n';
  const std::uint64_t row_bytes =
      h.bitmap() ? (static_cast<std::uint64_t>(h.width) + 7) / 8 : static_cast<std::uint64_t>(h.width) * h.channels();
  const std::uint64_t expected = row_bytes * static_cast<std::uint64_t>(h.height);
  const std::streamoff size = file->pubseekoff(0, std::ios::end, std::ios::in);
  const std::uint64_t present =
      size < static_cast<std::streamoff>(in.offset()) ? 0 : static_cast<std::uint64_t>(size) - in.offset();
  const std::string pixels = std::to_string(h.width) + " x " + std::to_string(h.height) + " pixels";
  if (present < expected)
    in.Fail(0, "pixels",
            std::to_string(present) + " of " + std::to_string(expected) + " raster bytes present (" + pixels +
                "): the file is truncated");
  if (present > expected)
    in.Fail(0, "pixels",
            std::to_string(present - expected) + (present - expected == 1 ? " byte follows" : " bytes follow") +
                " the raster of " + pixels +
                (crlf ? ": the header ends in CR LF, and Netpbm takes the LF as the first pixel (save it with LF "
                        "line ends)"
                      : " (a second image, or garbage; a map image holds one raster)"));
}

void CheckPlainRaster(PnmCursor& in, const PnmHeader& h) {
  const std::uint64_t expected =
      static_cast<std::uint64_t>(h.width) * static_cast<std::uint64_t>(h.height) * h.channels();
  auto pixel = [&](std::uint64_t sample) {
    const std::uint64_t index = sample / h.channels();
    return PixelField(static_cast<int>(index / h.width), static_cast<int>(index % h.width));
  };
  auto too_many = [&](long line) {
    in.Fail(line, "pixels",
            "more than the " + std::to_string(expected) + " values of " + std::to_string(h.width) + " x " +
                std::to_string(h.height) + " pixels");
  };
  std::uint64_t count = 0;
  if (h.bitmap()) {
    // One digit per sample, white space optional.
    for (in.SkipSpace(); in.Peek() != kEnd; in.SkipSpace()) {
      if (count == expected) too_many(in.line());
      const int c = in.Take();
      if (c != '0' && c != '1')
        in.Fail(in.line(), pixel(count), Shown(std::string(1, static_cast<char>(c))) + " is not 0 or 1");
      ++count;
    }
  } else {
    for (const std::string* token = &in.Token(); !token->empty(); token = &in.Token()) {
      if (count == expected) too_many(in.token_line());
      long value = 0;
      if (!PnmCursor::Whole(*token, &value))
        in.Fail(in.token_line(), pixel(count), Shown(*token) + " is not a whole number (digits only)");
      if (value > h.maxval)
        in.Fail(in.token_line(), pixel(count),
                "value " + *token + " is above the header's maxval " + std::to_string(h.maxval));
      ++count;
      // OpenCV reads one character past every number and fails at the end
      // of the file; Netpbm's own tools do not need it.
      if (count == expected && in.Peek() == kEnd)
        in.Fail(in.token_line(), "pixels",
                "the file ends right after the last value; end it with a line break, which OpenCV's reader needs");
    }
  }
  if (count < expected)
    in.Fail(0, "pixels", std::to_string(count) + " of " + std::to_string(expected) + " values present");
}

}  // namespace

void CheckPnmImage(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw InputError(path, 0, "", "cannot open image file");
  PnmCursor in(file.rdbuf(), path);
  const PnmHeader header = ReadHeader(in, path);
  if (header.binary())
    CheckBinaryRaster(in, file.rdbuf(), header);
  else
    CheckPlainRaster(in, header);
}

}  // namespace rc
